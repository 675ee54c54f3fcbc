// FrameAdmission's stop for every robot (frame_admission.h): taken whatever its address and
// never answered; with a room key only sealed under it, fresh by the room's window
// (security/room_freshness.h), whose top is this robot's clock; without one, plain, where the
// robot takes plain frames. A room stop whose counter lies past the clock's margin still
// stops the robot, and its counter is not kept: refusing it would leave a stop from a sender
// whose clock runs fast stopping nobody, and keeping it would make every true stop after it
// look old (docs/security.md, "What can stop a stop").
#include "command/command_payload.h"
#include "link/admission_verdicts.h"
#include "link/frame_admission.h"
#include "reliability/command_frame.h"
#include "reliability/sealed_frame.h"
#include "security/counter_clock.h"
#include "security/frame_mac.h"

namespace dtmf::link {

using admission::refuse;

namespace {

// A stop for every robot under the room key carries its whole counter (synchronisation form)
// and no payload: its MAC covers the payload the room key's frames always mean.
const std::uint32_t kRoomStopPayload = command::encode_payload(command::Stop{true});

security::FrameMacInput room_mac_input(const reliability::SealedFrame& f) {
  return {f.address, static_cast<std::uint8_t>(f.form), f.counter, kRoomStopPayload};
}

}  // namespace

bool FrameAdmission::admit_plain_room_stop(Reception& r) {
  const reliability::CommandFrame frame = *reliability::command_frame_unpack(r.bits.low64());
  const auto decoded = command::decode_payload(frame.payload);
  if (!decoded.command || !command::every_robot(*decoded.command)) return false;
  r.sequence = frame.sequence;
  r.answered = false;  // every robot heard it: no answer could say whose
  if (options_.room_key) {
    refuse(r, RefusalReason::Authentication,
           "an unauthenticated stop for every robot, and this robot takes one only under the room key (--room-key)");
  } else if (options_.key && !options_.accept_unauthenticated) {
    refuse(r, RefusalReason::Authentication,
           "an unauthenticated stop for every robot, and this robot has a key: a stop for every robot must come "
           "under the room key (dtmf-agent --room-key)");
  } else {
    take_command(r, *decoded.command);
  }
  return true;
}

bool FrameAdmission::room_authentic(const reliability::SealedFrame& frame) const {
  return options_.room_key && frame.form == reliability::SealedForm::Sync &&
         security::frame_mac(*options_.room_key, room_mac_input(frame)) == frame.mac;
}

bool FrameAdmission::admit_sealed_room_stop(Reception& r) {
  const reliability::SealedFrame frame = *reliability::sealed_frame_unpack(r.bits);
  if (!room_authentic(frame)) return false;
  r.answered = false;
  r.counter = frame.counter;
  r.mac_payload = kRoomStopPayload;
  const std::uint64_t clock = clock_counter();
  std::string note;
  // A window kept while its newest lay past this clock (before the bound, or a clock set
  // back) starts again below the clock, on disk too, before anything is checked against it.
  if (const auto kept = room_->reanchor(clock)) {
    options_.room_counters->reanchor(*kept);
    note = " (the room's window re-anchored to this robot's clock: its newest counter lay past it)";
  }
  switch (room_->check(frame.counter, clock)) {
    case security::Freshness::Stale:
      refuse(r, RefusalReason::Authentication,
             "a stop for every robot with room counter " + std::to_string(frame.counter) +
                 ", older than the room's window: a frame captured and played again" + note);
      return true;
    case security::Freshness::Repeat:  // the newest one's echo, or played again: stopped already
      r.authenticated = true;
      r.event = ReceptionEvent::Repeat;
      r.detail = "repeat of room counter " + std::to_string(frame.counter) + ", not executed again" + note;
      return true;
    case security::Freshness::Ahead:
      note += "; room counter " + std::to_string(frame.counter) + " lies " +
              admission::ahead_of_clock_words(frame.counter, clock) +
              ": stopped, the counter not kept (is a sender's clock fast, or this robot's slow?)";
      break;
    case security::Freshness::New:
      options_.room_counters->accept(frame.counter);  // kept before the stop acts (only the newest is)
      room_->take(frame.counter);
      break;
  }
  r.authenticated = true;
  take_command(r, command::Stop{true});
  r.detail += note;
  return true;
}

}  // namespace dtmf::link
