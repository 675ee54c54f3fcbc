// Reliability layer: listen before talk — when a sender may start its next frame on an air
// other senders share.
//
// Rules, from what its carrier sense (carrier_sense.h) heard:
// - Defer while another sounds, until the air has been heard quiet for `quiet_ms`: the
//   longest a robot of any profile this sender knows can stay silent between a frame's end
//   and its answer's start (ack_timeout_ms − chord_ms). So a frame never starts into an
//   answer another sender still waits for: a frame and its answer are one busy stretch.
//   Heard quiet: our own tail, which may hide another, must have fallen too.
//   Unless that sound ended with an answer the sender's ear read (it reads every robot's
//   answers in the profiles it knows): the exchange is over, nobody waits for an answer, and
//   kStarvedQuietMs of quiet will do. An answer it cannot read (another profile's, or too
//   weak) leaves the full hold, and so does an authenticated answer, which is only a tag
//   chord (the ear reads one out of mere noise; server/core/sender_core_ears.cpp).
// - Then back off at random (kBackoffSlots slots of kSlotMs, drawn once per deferral), so
//   that two senders that waited for the same quiet seldom start together. A slot is longer
//   than the time a start takes to be heard (the capture latency and a block).
// - Yield: once the room is known to be shared (another was heard within kSharedMemoryMs),
//   a sender whose frames have held the air for kMaxHoldMs pauses until the air has been
//   quiet for longer than the others' quiet hold and backoff, and then listens again like
//   them. A pause that has lasted kMaxDeferMs ends, and the frame defers like any other
//   (starved by then): a sender that never heard us never pauses as long as we wait, only
//   to listen, and a starved sender starts within that.
// - Listen: a sender that has heard nobody pauses after kListenEveryMs of its frames until
//   the air has been quiet for kListenWindowMs. While it sends, its own sound hides the
//   others (its microphone is beside its loudspeaker), so this is where it hears a sender
//   that waits for it.
// - A sender that has waited kMaxDeferMs for one frame (another that never heard it holds
//   the air) waits only for kStarvedQuietMs of quiet and a backoff of kStarvedSlots: it
//   starts in that sender's listening pause, after its exchange, so that it is heard there.
// - After a frame of ours went unanswered in a shared room (a collision, often with a sender
//   that started with us and will retransmit when we do), back off kLossSlots at random
//   before sending again, so that the two retransmissions do not meet again.
// - A stop goes first: it waits only while another sounds right now, with no quiet hold,
//   backoff or pause, and never longer than kMaxStopWaitMs (a sound that never ends, a
//   jammer, must not hold a stop back). It may fall on another's awaited answer (that sender
//   retransmits); it does not fall on a frame that will have ended by then.
// - A teleop renewal never pauses: a lease must not lapse while its operator holds a key.
//   It still defers to another's sound.
// - A stop for every robot never waits: every robot must stop, and no robot answers it, so
//   there is no exchange of ours to protect either.
// - Whatever held it, a command waits for the air at most kMaxDeferToUnknownMs in all, its
//   frames and retransmissions together (AirWait), and then goes out into the sound, as it
//   would without listening. The carrier sense cannot tell another sender's frame from a
//   jammer's noise (it measures levels), and the one thing it reads, an answer, anyone can
//   play; so no sound is trusted to hold a command longer. Summed, not measured from the last
//   quiet: a sound that leaves a short quiet now and then renews nothing. The sound that held
//   it goes on, so the next wait starts starved, until the air has been heard quiet for the
//   hold: a sender that never heard us (it pauses to listen only every kListenEveryMs) is
//   thus still met in its listening pause, as a sender that waited all along would be.
// A sender alone pays one listening pause (its tail's fall and kListenWindowMs) per
// kListenEveryMs of frames sent back to back, and nothing when its frames leave gaps.
//
// Pure logic: the caller passes its clock reading; the random draws come from the seeded
// generator it is given.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>

#include "reliability/carrier_sense.h"

namespace dtmf::reliability {

inline constexpr double kSlotMs = 50;              // a start is heard within a slot
inline constexpr int kBackoffSlots = 8;            // backoff: 0..7 slots
inline constexpr double kMaxHoldMs = 2000;         // a run of our frames, in a shared room
inline constexpr double kSharedMemoryMs = 60'000;  // another heard this recently: shared
inline constexpr double kListenEveryMs = 20'000;   // a run of our frames, alone
inline constexpr int kStarvedSlots = 3;            // a starved sender's backoff: 0..2 slots
// A starved sender's quiet: longer than the capture latency during which a sender whose
// exchange just ended cannot tell another's start from its own sound.
inline constexpr double kStarvedQuietMs = kOwnLatencyMs + kSlotMs;
// The listening pause's quiet outlasts a starved sender's quiet, backoff and start.
inline constexpr double kListenWindowMs = kStarvedQuietMs + (kStarvedSlots + 1) * kSlotMs;
inline constexpr double kMaxDeferMs = 4000;           // waited this long: starved
inline constexpr double kBusyNowMs = kOwnLatencyMs;   // a stop waits while sound is this fresh
inline constexpr double kMaxStopWaitMs = 400;         // ... at most this long: a frame and its answer
inline constexpr int kLossSlots = 2 * kBackoffSlots;  // after a loss in a shared room: 0..15 slots
// One deferral to a real sender of this software ends within this: once it has heard us it
// holds the air for one run, kMaxHoldMs and the exchange under way (the slowest profile's:
// seed, 1500 ms to its answer's timeout and a 300 ms answer), 3800 ms of sound, then pauses;
// by then we are starved (kMaxDeferMs), and start after kStarvedQuietMs of quiet heard
// kOwnLatencyMs late and at most kStarvedSlots - 1 slots of backoff. 4350 ms.
inline constexpr double kStarvedDeferralMs =
    kMaxDeferMs + kOwnLatencyMs + kStarvedQuietMs + (kStarvedSlots - 1) * kSlotMs;
// A command may need two: its first frame's, and one more for a retransmission after a
// collision, or for a seed command's later frames after its own run yielded (three frames of
// 1.1-1.8 s outlast kMaxHoldMs).
inline constexpr int kDeferralsPerCommand = 2;
// The most one command waits for the air, its frames and retransmissions together, for any
// sound (none is known to be a frame: see above). 8700 ms: what an attacker can add to each
// command, where a sound leaving short quiets held one for good, and a steady one up to
// kFloorWindowMs (30 s) until the floor took it in. Not a stop (kMaxStopWaitMs).
inline constexpr double kMaxDeferToUnknownMs = kDeferralsPerCommand * kStarvedDeferralMs;

// What a frame is, for the air's rules.
enum class AirUse { Command, Renewal, Stop, EveryRobotStop };

// Why a frame waits for the air, as the rules above and the carrier sense can tell.
enum class AirWaitCause {
  None,
  Sound,             // sound over the room's floor: another sender's, or anyone's
  AnsweredExchange,  // another's exchange, ended by an answer the ear read: the short quiet
  MaskedAnswer,      // another's robot answered under our last exchange
  Yield,             // our run in a shared room: the others' turn
  Listen,            // our long run, alone: listening for a sender that waits for us
  LossBackoff,       // our last frame went unanswered in a shared room
};
struct AirWaitReason {
  AirWaitCause cause = AirWaitCause::None;
  double over_floor_db = 0;  // Sound: the last busy block's level over the room's floor
};
// For the operator: "sound 14 dB over the room's floor", "yielding to another sender", ...
std::string air_wait_text(const AirWaitReason& reason);

// One command's waits for the air: each start's, and the one under way. The caller keeps one
// per command and hands it to every start_at() and started() of its frames, so that
// kMaxDeferToUnknownMs bounds their sum.
struct AirWait {
  double held_ms = 0;              // waits that ended in a start
  double last_ms = 0;              // ... the last start's
  int waits = 0;                   // starts that waited
  std::optional<double> since_ms;  // the wait under way began here
  AirWaitReason reason;            // ... for this reason
  double total_ms(double now_ms) const { return held_ms + (since_ms ? now_ms - *since_ms : 0); }
};

class AirAccess {
 public:
  AirAccess(double quiet_ms, std::uint64_t seed) : quiet_ms_(quiet_ms), random_(seed) {}

  // The earliest time from `now_ms` our next frame may start (`now_ms` itself: at once).
  // Call again at that time: a sound heard meanwhile moves it. `wait`: the frame's command's
  // (a wait that begins is marked in it, with its reason); without it, the bound is the start's own.
  double start_at(const CarrierSense& sense, double now_ms, AirUse use, AirWait& wait);
  double start_at(const CarrierSense& sense, double now_ms, AirUse use) {
    return start_at(sense, now_ms, use, own_wait_);
  }
  // Our frame starts at `at_ms` (after start_at said so); its wait joins `wait`.
  void started(const CarrierSense& sense, double at_ms, AirWait& wait);
  void started(const CarrierSense& sense, double at_ms) {
    started(sense, at_ms, own_wait_);
    own_wait_ = {};
  }
  // Our frame's exchange ended at `at_ms` without the answer it asked for.
  void unanswered(const CarrierSense& sense, double at_ms);

  // How many frames had to wait for another's sound, and how many pauses we made (to yield
  // in a shared room, or to listen alone).
  std::uint64_t deferred() const { return deferred_; }
  // How many of those started after the short quiet, their wait ended by an answer we read.
  std::uint64_t answered_waits() const { return answered_waits_; }
  std::uint64_t yields() const { return yields_; }
  std::uint64_t listens() const { return listens_; }

 private:
  bool shared(const CarrierSense& sense, double now_ms) const;
  // The rules above but the bound; `why`: what holds the frame, if anything does.
  double rules_at(const CarrierSense& sense, double now_ms, AirUse use, AirWaitReason& why);
  double stop_at(const CarrierSense& sense, double now_ms, AirWaitReason& why);
  double draw_backoff_ms(int slots);
  // The pause our run owes from `now_ms`, if it owes one: the quiet still to be heard.
  std::optional<double> pause_left_ms(const CarrierSense& sense, double now_ms, bool shared);

  double quiet_ms_;
  std::mt19937_64 random_;
  std::optional<double> backoff_ms_;  // drawn for the deferral under way
  std::optional<double> deferred_since_ms_;
  bool starved_ = false;
  bool answered_ = false;                // the deferral under way waits the short quiet after an answer
  std::optional<double> not_before_ms_;  // after an unanswered frame
  std::optional<double> stop_asked_ms_;  // when the stop waiting for the air first asked
  std::optional<double> run_start_ms_;
  bool pausing_ = false;
  double pause_since_ms_ = 0;  // while pausing_
  std::uint64_t deferred_ = 0, yields_ = 0, listens_ = 0, answered_waits_ = 0;
  AirWait own_wait_;  // for callers that keep none
  // Whether the start start_at() allowed last was the bound's (true) or the air's (false);
  // nothing for a stop's, or a command's whose bound was spent already.
  std::optional<bool> bound_start_;
  bool held_over_ = false;  // our last wait ended by the bound: the next starts starved
};

}  // namespace dtmf::reliability
