// The joint renewal's planner (renewal_planner.h): picks the robots, numbers the frame once for
// all of them, fills a slot per robot (keyed: an 18-bit MAC under its key, bound to its
// velocity's counter; plain: its velocity's sequence number) and sounds the frame as the
// fast link sounds its own (fast_frames.h).
#include "link/renewal_planner.h"

#include <algorithm>
#include <string>

#include "link/fast_frames.h"
#include "reliability/plain_renewal.h"
#include "reliability/renewal_frame.h"
#include "security/frame_mac.h"
#include "security/freshness.h"

namespace dtmf::link {

namespace {

static_assert(reliability::kPlainRenewalSlots == reliability::kRenewalSlots, "one count of slots for both kinds");

bool has_velocity(const RenewalParty& party) {
  return party.key ? party.record.velocity_counter.has_value() : party.record.velocity_sequence.has_value();
}

// Slots nobody fills repeat the first: a robot checks the same slot twice, no other robot's.
template <typename Slots>
void repeat_first_slot(Slots& slots, std::size_t filled) {
  for (std::size_t slot = filled; slot < slots.size(); ++slot) slots[slot] = slots[0];
}

RenewalPlan plan_keyed(const LinkProfile& profile, std::span<const RenewalParty> parties,
                       const std::vector<std::size_t>& candidates) {
  RenewalPlan plan;
  plan.numbered = candidates;
  std::uint64_t counter = 0;  // one counter, new to every one of them
  for (const std::size_t i : candidates) {
    if (!parties[i].fresh_counter)
      throw std::invalid_argument("a joint renewal of robot " + std::to_string(parties[i].address) +
                                  " needs a fresh counter from its store");
    counter = std::max(counter, *parties[i].fresh_counter);
  }
  plan.counter = counter;
  reliability::RenewalFrame renewal;
  renewal.counter_low = security::counter_low_bits(counter);
  for (const std::size_t i : candidates) {
    const RenewalParty& party = parties[i];
    const std::uint64_t velocity_counter = *party.record.velocity_counter;
    // The robot completes the low bits from its velocity frame's counter: one that could not
    // is left out, and its next frame, numbered after this one, is in step again.
    if (counter - velocity_counter >= security::kCounterWindow) continue;
    const std::uint32_t mac =
        security::frame_mac(*party.key, security::renewal_mac_input(party.address, counter, velocity_counter));
    renewal.slots[plan.renewed.size()] = {party.address, mac >> (32 - reliability::kRenewalMacBits)};
    plan.renewed.push_back(i);
  }
  if (plan.renewed.empty()) return plan;
  repeat_first_slot(renewal.slots, plan.renewed.size());
  plan.frame = renewal_transmit_frame(profile, renewal, counter);
  return plan;
}

RenewalPlan plan_plain(const LinkProfile& profile, std::span<const RenewalParty> parties,
                       const std::vector<std::size_t>& candidates) {
  RenewalPlan plan;
  plan.numbered = candidates;
  plan.renewed = candidates;
  std::uint64_t number = 0;  // one number, new to every one of them
  for (const std::size_t i : candidates) number = std::max(number, parties[i].record.next_renewal_number);
  plan.next_renewal_number = number + 1;
  reliability::PlainRenewal renewal;
  renewal.number = static_cast<std::uint32_t>(number & reliability::kPlainRenewalNumberMask);
  for (std::size_t slot = 0; slot < candidates.size(); ++slot) {
    const RenewalParty& party = parties[candidates[slot]];
    renewal.slots[slot] = {party.address, *party.record.velocity_sequence};
  }
  repeat_first_slot(renewal.slots, candidates.size());
  TransmitFrame f = command_transmit_frame(profile, reliability::plain_renewal_pack(renewal));
  f.sequence.reset();  // no answer names it
  f.address = renewal.slots[0].address;
  f.renewal = true;
  plan.frame = std::move(f);
  return plan;
}

}  // namespace

std::vector<std::size_t> renewal_candidates(std::span<const RenewalParty> parties) {
  const bool any_keyed = std::any_of(parties.begin(), parties.end(), [](const RenewalParty& p) { return p.key; });
  const bool any_plain = std::any_of(parties.begin(), parties.end(), [](const RenewalParty& p) { return !p.key; });
  if (any_keyed && any_plain)
    throw MixedRenewal(
        "a joint renewal renews keyed robots or robots without keys, not both in one frame: a plain renewal, "
        "which anyone can play, must not renew a keyed robot; renew each kind with a frame of its own");
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < parties.size() && candidates.size() < reliability::kRenewalSlots; ++i) {
    if (has_velocity(parties[i])) candidates.push_back(i);
  }
  return candidates;
}

RenewalPlan plan_joint_renewal(const LinkProfile& profile, std::span<const RenewalParty> parties) {
  const std::vector<std::size_t> candidates = renewal_candidates(parties);
  if (candidates.empty()) return {};
  if (parties[candidates.front()].key) return plan_keyed(profile, parties, candidates);
  return plan_plain(profile, parties, candidates);
}

}  // namespace dtmf::link
