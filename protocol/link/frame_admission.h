// The fast profile's robot, past the receive path: what a frame heard means — a command to
// execute, the last frame again, a counter synchronisation, or a refusal, and why.
//
//   a 50-bit frame (unauthenticated): for this robot's address? with a key, refused unless
//       unauthenticated frames are let in; the payload a command? the sequence filter:
//       a retransmission after a lost ACK is answered, not executed again
//   an 80-bit frame (authenticated): for this robot's address? without a key, refused;
//       the counter completed from its low bits (a synchronisation carries all of it), the
//       MAC checked over address, form, counter and payload; a counter not newer than the
//       last accepted is the last frame again (answered, not executed) or refused; a new one
//       is kept (security/counter_store.h) before the frame acts; one more than
//       kClockMarginS ahead of this robot's clock (security/counter_clock.h) is neither taken
//       nor kept, and refused, unless the frame is a Stop, which stops the robot all the same
//   a Stop carries its whole counter (synchronisation form, its MAC over STOP): a robot out of
//       step places it with no synchronisation before it, and is in step after it
// A frame for another robot is nobody's business here: no reception at all; nor is an echo of
// a frame taken lately, other than the newest (reliability/echo_memory.h). A frame this robot
// cannot check (another key's, sealed without a key, plain where only sealed ones are taken)
// is refused and left unanswered, and a broken one is NACKed only where its address reads
// as this robot's (Reception::answered): another robot's answer must not sound over its own.
// A stop for every robot is taken whatever its address and never answered: with a room key
// only sealed under it, in synchronisation form with its whole counter, fresh by the room's
// window (security/room_freshness.h), whose top is this robot's clock; one past it still
// stops the robot, its counter not kept; without one, plain, where the robot takes plain frames.
// A plain joint renewal (reliability/plain_renewal.h), for robots without keys, is taken from
// the slot that names this robot when it names the sequence number of the plain velocity
// frame taken last: that velocity again, never answered; its number taken once per velocity.
// A joint renewal (reliability/renewal_frame.h) is taken from whichever slot names this
// robot and whose MAC holds under its key for the renewal's counter and the counter of the
// velocity frame it took last: that velocity again, its lease from the renewal's start,
// never answered; a renewal of any other frame, or after another command, fails its MAC.
// Its counter is completed from the velocity frame's, not from the last accepted, and is
// kept apart from the commands' (each taken once, as IPsec's window keeps them): so a forged
// renewal that got through cannot make the sender's next frames stale. A velocity is renewed
// for at most kRenewalHorizonMs after its own frame began: the sender sends the velocity
// again, answered, every 5 s (server/teleop_session.h), and a recording of renewals the
// robot missed cannot hold it longer than that. A renewal renews only a lease still running:
// one that begins after the lease ran out (the robot stopped) renews nothing, so a renewal the
// air delayed, or a recording of one, never sets a stopped robot moving again; only a new
// velocity frame does.
// Where a slot holds by chance (one in 2^18) in this robot's command whose MAC holds, the
// frame is the command; a frame sealed under the room key is the stop for every robot.
// How: a frame heard is read once into one kind (frame_reading.h), every reading its MAC could
// decide verified first and one chosen by a stated rule where two hold; then the kind's one
// condition that holds picks a row of the rules (admission_rules.h), which says the event,
// the answer and whether the counter is kept, and the admission does what the row says.
// Pure logic, but for the counter stores and the wall clock it is given. Parts:
// room_stop_admission.cpp (the stop for every robot), renewal_admission.cpp (joint renewals).
#pragma once

#include <optional>
#include <set>

#include "link/admission_rules.h"
#include "link/frame_reading.h"
#include "link/hop_frame_path.h"
#include "link/link.h"
#include "reliability/echo_memory.h"
#include "reliability/sequence_filter.h"
#include "security/frame_mac.h"
#include "security/room_freshness.h"

namespace dtmf::link {

// How long after a velocity frame began renewals may still renew it.
inline constexpr double kRenewalHorizonMs = 6000;

class FrameAdmission {
 public:
  FrameAdmission(const LinkProfile& profile, const LinkOptions& options);
  // The reception of `heard`, or nothing for a frame addressed to another robot or an echo.
  std::optional<Reception> admit(const HeardHopFrame& heard);
  // Echoes of frames taken lately, ignored so far.
  std::size_t echoes_ignored() const { return echoes_ignored_; }
  // Whether the 80-bit frame `bits` (its CRC holds) is authentic: some reading of it verifies
  // (reading::verify_sealed). Changes nothing, allocates nothing; false without a key.
  bool authentic(const reliability::FrameBits& bits) const;

 private:
  using Rule = admission::Rule;
  using Condition = admission::Condition;

  // This robot's keys and state as a frame's reading needs them.
  reading::ReadingContext reading_context() const;
  // Gives `r` the row of (`kind`, `condition`): its event, refusal, answer, authentication.
  const Rule& judge(reading::FrameKind kind, Condition condition, Reception& r) const;
  // One for each kind of frame read: finds its condition, judges it by its row of
  // kAdmissionRules and does what the row says. Unheard: no reception.
  const Rule& act(const reading::Broken& frame, Reception& r);
  const Rule& act(const reading::Echo& frame, Reception& r);
  const Rule& act(const reading::Elsewhere& frame, Reception& r);
  const Rule& act(const reading::PlainCommand& frame, Reception& r);
  const Rule& act(const reading::Synchronisation& frame, Reception& r);
  const Rule& act(const reading::SealedCommand& frame, Reception& r);
  const Rule& act(const reading::Unverified& frame, Reception& r);
  // room_stop_admission.cpp: the stop for every robot.
  const Rule& act(const reading::PlainRoomStop& frame, Reception& r);
  const Rule& act(const reading::RoomStop& frame, Reception& r);
  // renewal_admission.cpp: joint renewals.
  const Rule& act(const reading::PlainRenewal& frame, Reception& r);
  const Rule& act(const reading::JointRenewal& frame, Reception& r);

  // Whether plain (unauthenticated) frames are refused here: a key, and no exception made.
  bool plain_refused() const { return options_.key && !options_.accept_unauthenticated; }
  // This robot's clock as a counter (security/counter_clock.h).
  std::uint64_t clock_counter() const;
  // A renewal `id` (its counter, or a plain renewal's number) of the velocity taken last,
  // beginning at `start_ms`: PastHorizon, LeaseEnded, Repeat or Fresh.
  Condition renewal_condition(double start_ms, std::uint64_t id) const;
  // What a renewal `id`, described as `what`, did under `condition`: renewed the velocity
  // (Fresh), or the words why not.
  void renew(Condition condition, Reception& r, std::uint64_t id, const std::string& what);
  // Executes `command`: nothing taken before it is renewed any more, and its echoes are known.
  void take_command(Reception& r, const command::Command& command);
  // After `command` was taken from the frame of `r`: if a velocity, what renewals renew next,
  // known by `id` (its counter if `sealed`, else its sequence number).
  void hold_renewable(const Reception& r, const command::Command& command, std::uint64_t id, bool sealed);

  // The velocity frame taken last, while no other command has been taken since: what a
  // renewal renews (a keyed renewal only a sealed one, a plain renewal only a plain one).
  struct Renewable {
    std::uint64_t counter = 0;  // sealed: its counter; plain: its sequence number
    command::Velocity velocity;
    double start_ms = 0;              // when its frame began
    double lease_ends_ms = 0;         // when its lease runs out, renewals taken counted
    std::set<std::uint64_t> renewed;  // the renewals taken: their counters, or plain renewals' numbers
    bool sealed = false;
  };
  std::optional<Renewable> renewable_;

  const LinkProfile& profile_;
  LinkOptions options_;
  reliability::SequenceFilter sequence_;
  reliability::EchoMemory echoes_;
  std::size_t echoes_ignored_ = 0;
  std::optional<security::RoomFreshness> room_;  // with a room key
};

// The MAC input of an authenticated frame the robot took: its counter as completed, and the
// payload its MAC held for (Reception::mac_payload).
security::FrameMacInput sealed_mac_input(const Reception& r);

}  // namespace dtmf::link
