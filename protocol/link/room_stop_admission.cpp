// FrameAdmission's stop for every robot (frame_admission.h): taken whatever its address and
// never answered; with a room key only sealed under it, fresh by the room's window
// (security/room_freshness.h), whose top is this robot's clock; without one, plain, where the
// robot takes plain frames. A room stop whose counter lies past the clock's margin still
// stops the robot, and its counter is not kept: refusing it would leave a stop from a sender
// whose clock runs fast stopping nobody, and keeping it would make every true stop after it
// look old (docs/security.md, "What can stop a stop"). Its rows: admission_rules.h.
#include "command/command_payload.h"
#include "link/admission_verdicts.h"
#include "link/frame_admission.h"
#include "security/counter_clock.h"

namespace dtmf::link {

using admission::Condition;
using reading::FrameKind;

const admission::Rule& FrameAdmission::act(const reading::PlainRoomStop& frame, Reception& r) {
  r.sequence = frame.frame.sequence;
  const Condition condition = options_.room_key ? Condition::RoomKeyHeld
                              : plain_refused() ? Condition::KeyedRobot
                                                : Condition::Fresh;
  const Rule& rule = judge(FrameKind::PlainRoomStop, condition, r);  // every robot heard it: no answer could say whose
  switch (condition) {
    case Condition::RoomKeyHeld:
      r.detail =
          "an unauthenticated stop for every robot, and this robot takes one only under the room key (--room-key)";
      break;
    case Condition::KeyedRobot:
      r.detail =
          "an unauthenticated stop for every robot, and this robot has a key: a stop for every robot must come "
          "under the room key (dtmf-agent --room-key)";
      break;
    default:
      take_command(r, command::Stop{true});
      break;
  }
  return rule;
}

const admission::Rule& FrameAdmission::act(const reading::RoomStop& frame, Reception& r) {
  r.counter = frame.room_counter;
  r.mac_payload = frame.payload;
  const std::uint64_t clock = clock_counter();
  std::string note;
  // A window kept while its newest lay past this clock (before the bound, or a clock set
  // back) starts again below the clock, on disk too, before anything is checked against it.
  if (const auto kept = room_->reanchor(clock)) {
    options_.room_counters->reanchor(*kept);
    note = " (the room's window re-anchored to this robot's clock: its newest counter lay past it)";
  }
  Condition condition = Condition::Fresh;
  switch (room_->check(frame.room_counter, clock)) {
    case security::Freshness::Stale:
      condition = Condition::Stale;
      break;
    case security::Freshness::Repeat:  // the newest one's echo, or played again: stopped already
      condition = Condition::Repeat;
      break;
    case security::Freshness::Ahead:
      condition = Condition::Ahead;
      break;
    case security::Freshness::New:
      break;
  }
  const Rule& rule = judge(FrameKind::RoomStop, condition, r);
  if (rule.keeps_counter) {  // kept before the stop acts (only the newest is)
    options_.room_counters->accept(frame.room_counter);
    room_->take(frame.room_counter);
  }
  const std::string counter = std::to_string(frame.room_counter);
  switch (condition) {
    case Condition::Stale:
      r.detail = "a stop for every robot with room counter " + counter +
                 ", older than the room's window: a frame captured and played again" + note;
      break;
    case Condition::Repeat:
      r.detail = "repeat of room counter " + counter + ", not executed again" + note;
      break;
    case Condition::Ahead:
      note += "; room counter " + counter + " lies " + admission::ahead_of_clock_words(frame.room_counter, clock) +
              ": stopped, the counter not kept (is a sender's clock fast, or this robot's slow?)";
      [[fallthrough]];
    default:
      take_command(r, command::Stop{true});
      r.detail += note;
      break;
  }
  return rule;
}

}  // namespace dtmf::link
