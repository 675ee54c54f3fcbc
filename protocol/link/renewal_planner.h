// The sender's joint renewal (docs/protocol.md §10, "Renewing leases together"), planned in
// one place for all the robots it renews: given each robot's address, key and what its sender
// sent it last, the one unanswered frame to play and what the renewal does to each robot's
// numbers. Keyed robots get an authenticated frame, each slot under its robot's own key
// (reliability/renewal_frame.h); robots without keys a 50-bit frame (reliability/plain_renewal.h).
//
// One frame never mixes the two: a plain renewal, which anyone can play, must not renew a
// keyed robot, and a keyed frame has no slot a plain robot could check, so a caller that
// offers both is told so (MixedRenewal) rather than having robots quietly left out.
//
// Pure: no I/O, no clock, and no link of its own. The caller draws each keyed robot's fresh
// counter from its store before and applies the plan after (Link::plan_renewal, link.h, does
// both for the robots' links), so that a store on disk is touched by its owner alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "link/transmit_plan.h"
#include "profile/link_profile.h"
#include "security/link_key.h"

namespace dtmf::link {

// What a sender keeps of one robot for its joint renewals, kept up as its frames are planned.
struct RenewalRecord {
  // Keyed: the counter of the last frame planned for the robot, when that was a velocity
  // (what a renewal renews, and binds its slot to).
  std::optional<std::uint64_t> velocity_counter;
  // Plain: the sequence number of the last frame planned, when that was a velocity.
  std::optional<std::uint8_t> velocity_sequence;
  // Plain: the least number its next renewal takes (a robot takes each renewal's number once).
  std::uint64_t next_renewal_number = 0;
};

// One robot as the planner sees it.
struct RenewalParty {
  std::uint8_t address = 0;
  const security::LinkKey* key = nullptr;  // its own key; none: it is renewed by plain frames
  RenewalRecord record;
  // Keyed candidates (renewal_candidates): a counter its store handed out for this renewal and
  // for nothing before (security::CounterStore::next_counter).
  std::optional<std::uint64_t> fresh_counter;
};

// A joint renewal planned: the frame, and what its caller must record.
struct RenewalPlan {
  // None when no robot can be renewed; the numbers below may still have been used.
  std::optional<TransmitFrame> frame;
  std::vector<std::size_t> renewed;   // the parties its slots renew: at most three, in order
  std::vector<std::size_t> numbered;  // the parties whose numbers it used, renewed or not
  // Keyed: the frame's one counter. Every numbered party's store must hand out no counter at
  // or below it from now on, whether or not its robot was renewed (its next frame is then in
  // step again: it carries its whole counter if it must).
  std::optional<std::uint64_t> counter;
  // Plain: every numbered party's next_renewal_number from now on.
  std::optional<std::uint64_t> next_renewal_number;
};

// Keyed and plain robots offered for one renewal.
class MixedRenewal : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The parties a renewal would number: the first three (reliability::kRenewalSlots) whose last
// frame planned was a velocity. Throws MixedRenewal when `parties` holds keyed and plain robots.
std::vector<std::size_t> renewal_candidates(std::span<const RenewalParty> parties);

// The joint renewal of `parties` under `profile` (the fast profile's frames). Keyed, its
// counter is the greatest of the candidates' fresh counters, so it is new to every one of
// them; a robot that could not complete it from its velocity's counter (a window or more
// apart, security/freshness.h) is left out. Plain, its number is the greatest of the
// candidates' next numbers. Slots nobody fills repeat the first: a robot then checks its own
// slot twice, never another's. Throws MixedRenewal (see above), and std::invalid_argument for
// a keyed candidate without a fresh counter.
RenewalPlan plan_joint_renewal(const LinkProfile& profile, std::span<const RenewalParty> parties);

}  // namespace dtmf::link
