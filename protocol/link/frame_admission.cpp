#include "link/frame_admission.h"

#include <algorithm>

#include "command/command_payload.h"
#include "reliability/command_frame.h"
#include "reliability/plain_renewal.h"
#include "reliability/renewal_frame.h"
#include "reliability/sealed_frame.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {
// A velocity's lease, from a frame that began at `start_ms` (the robot counts it so).
double lease_end(const command::Velocity& velocity, double start_ms) { return start_ms + 1000 * velocity.lease_s; }

void refuse(Reception& r, RefusalReason reason, std::string why) {
  r.event = ReceptionEvent::Refused;
  r.refusal = reason;
  r.detail = std::move(why);
}

// A frame this robot cannot check may be another robot's (its own key, or none): refused
// here, and left for that robot to answer.
void refuse_unchecked(Reception& r, std::string why) {
  refuse(r, RefusalReason::Authentication, std::move(why));
  r.answered = false;
}

// The address a frame's bits name, read even where its check failed (its top three bits).
std::uint8_t address_read(const reliability::FrameBits& bits, int bit_count) {
  return static_cast<std::uint8_t>((bits.value() >> (bit_count - reliability::kAddressBits)) &
                                   reliability::kAddressMask);
}

}  // namespace

namespace {

security::FrameMacInput mac_input(const reliability::SealedFrame& f, std::uint64_t counter) {
  return {f.address, static_cast<std::uint8_t>(f.form), counter, f.payload};
}

// A stop for every robot under the room key carries its whole counter (synchronisation form)
// and no payload: its MAC covers the payload the room key's frames always mean.
const std::uint32_t kRoomStopPayload = command::encode_payload(command::Stop{true});

security::FrameMacInput room_mac_input(const reliability::SealedFrame& f) {
  return {f.address, static_cast<std::uint8_t>(f.form), f.counter, kRoomStopPayload};
}

// The counter a frame stands for, after the last accepted: a synchronisation carries all of
// it, a command its low bits (security/freshness.h).
std::uint64_t completed_counter(const reliability::SealedFrame& f, std::uint64_t last_accepted) {
  return f.form == reliability::SealedForm::Sync
             ? f.counter
             : security::complete_counter(last_accepted, static_cast<std::uint32_t>(f.counter));
}

}  // namespace

security::FrameMacInput sealed_mac_input(const reliability::FrameBits& bits, std::uint64_t counter) {
  const auto f = reliability::sealed_frame_unpack(bits);
  return f ? mac_input(*f, counter) : security::FrameMacInput{};
}

FrameAdmission::FrameAdmission(const LinkProfile& profile, const LinkOptions& options)
    : profile_(profile),
      options_(options),
      // Within this, the sender cannot have sent 15 new frames: no sequence number comes round.
      echoes_(static_cast<double>(reliability::EchoMemory::kFramesRemembered) * 1000.0 *
              profile.hops().frame_samples() / profile.sample_rate_hz) {
  if (options_.room_key) room_.emplace(options_.room_counters->last_accepted());
}

std::optional<Reception> FrameAdmission::admit(const HeardHopFrame& heard) {
  Reception r;
  r.start_ms = heard.start_ms;
  r.heard_ms = heard.heard_ms;
  r.bits = heard.bits;
  r.intact = heard.intact;
  const bool sealed = heard.chords == profile_.hops().sealed_chords_per_frame;
  r.bit_count = sealed ? reliability::kSealedFrameBits : reliability::kCommandFrameBits;
  r.check_bit_count = sealed ? reliability::kSealedCheckBits : reliability::kCommandCrcBits;
  const std::vector<double> tones =
      sealed ? signal::frame_tones_hz(profile_, reliability::sealed_frame_symbols(heard.bits))
             : signal::frame_tones_hz(profile_, reliability::command_frame_symbols(heard.bits.low64()));
  r.tones_hz = tones;
  // Broken: NACKed where its address reads as this robot's. Another robot's damaged frame is
  // not this one's to complain about: its NACK would sound over that robot's ACK.
  if (!r.intact) {
    r.answered = address_read(heard.bits, r.bit_count) == options_.address;
    return r;
  }
  if (echoes_.is_echo(r.bits, r.heard_ms)) {  // the room's, not the sender's: not ours to answer
    ++echoes_ignored_;
    return std::nullopt;
  }
  // Every robot's, whatever its address.
  if (sealed ? admit_sealed_room_stop(r) : admit_plain_room_stop(r)) return r;
  const std::uint8_t address = sealed ? reliability::sealed_frame_unpack(heard.bits)->address
                                      : reliability::command_frame_unpack(heard.bits.low64())->address;
  // Up to three robots', whatever the address its first bits read as; but a frame whose
  // 32-bit MAC holds as this robot's command is that command (one in 2^18 would pass a slot's
  // MAC by chance: a stop taken for a renewal would be neither executed nor answered).
  const bool my_command = sealed && address == options_.address && command_authentic(heard.bits);
  if (sealed && !my_command && admit_renewal(r)) return r;
  if (!sealed) {
    if (const auto renewal = reliability::plain_renewal_unpack(*reliability::command_frame_unpack(heard.bits.low64())))
      return admit_plain_renewal(std::move(r), *renewal);
  }
  if (address != options_.address) return std::nullopt;  // another robot's frame: not ours to answer either
  if (sealed)
    admit_sealed(r);
  else
    admit_plain(r);
  return r;
}

void FrameAdmission::admit_plain(Reception& r) {
  const reliability::CommandFrame frame = *reliability::command_frame_unpack(r.bits.low64());
  r.sequence = frame.sequence;
  if (options_.key && !options_.accept_unauthenticated) {
    refuse_unchecked(
        r, "an unauthenticated frame, and this robot has a key (dtmf-agent --accept-unauthenticated lets them in)");
    return;
  }
  const auto decoded = command::decode_payload(frame.payload);
  if (!decoded.command) {
    refuse(r, RefusalReason::Payload, decoded.error);  // passed the checks by chance, or a kind this robot lacks
    return;
  }
  if (!sequence_.first_time(frame)) {
    r.event = ReceptionEvent::Repeat;
    r.detail = "repeat, not executed again";
    return;
  }
  take_command(r, *decoded.command);
  if (const auto* velocity = std::get_if<command::Velocity>(&*decoded.command))
    renewable_ = Renewable{frame.sequence, *velocity, r.start_ms, lease_end(*velocity, r.start_ms), {}, false};
}

std::optional<Reception> FrameAdmission::admit_plain_renewal(Reception r, const reliability::PlainRenewal& renewal) {
  const auto slot = std::find_if(renewal.slots.begin(), renewal.slots.end(),
                                 [&](const reliability::PlainRenewalSlot& s) { return s.address == options_.address; });
  if (slot == renewal.slots.end()) return std::nullopt;  // other robots' renewal
  r.answered = false;                                    // up to three robots heard it: answers would sound together
  r.sequence = slot->sequence;
  if (options_.key && !options_.accept_unauthenticated) {
    refuse_unchecked(
        r, "an unauthenticated renewal, and this robot has a key (dtmf-agent --accept-unauthenticated lets them in)");
    return r;
  }
  // Only a plain velocity: a plain renewal of a sealed one would let anyone keep a keyed robot moving.
  if (!renewable_ || renewable_->sealed || renewable_->counter != slot->sequence) {
    r.event = ReceptionEvent::Ignored;
    r.detail = "a renewal of the velocity frame numbered " + std::to_string(slot->sequence) +
               ", not the velocity this robot took last (it missed that frame or took a command since): renews nothing";
    return r;
  }
  // Past the horizon: not what its sender sends (it sends the velocity again every 5 s).
  take_renewal(
      r, renewal.number,
      "renewal " + std::to_string(renewal.number) + " of the velocity numbered " + std::to_string(slot->sequence),
      RefusalReason::Payload);
  return r;
}

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
  switch (room_->check(frame.counter)) {
    case security::Freshness::Stale:
      refuse(r, RefusalReason::Authentication,
             "a stop for every robot with room counter " + std::to_string(frame.counter) +
                 ", older than the room's window: a frame captured and played again");
      return true;
    case security::Freshness::Repeat:  // the newest one's echo, or played again: stopped already
      r.authenticated = true;
      r.event = ReceptionEvent::Repeat;
      r.detail = "repeat of room counter " + std::to_string(frame.counter) + ", not executed again";
      return true;
    case security::Freshness::New:
      break;
  }
  options_.room_counters->accept(frame.counter);  // kept before the stop acts (only the newest is)
  room_->take(frame.counter);
  r.authenticated = true;
  take_command(r, command::Stop{true});
  return true;
}

std::optional<std::uint64_t> FrameAdmission::renewal_counter(const reliability::FrameBits& bits) const {
  if (!options_.key || !renewable_ || !renewable_->sealed) return std::nullopt;
  const auto renewal = reliability::renewal_frame_unpack(bits);
  if (!renewal) return std::nullopt;
  const std::uint64_t counter = security::complete_counter(renewable_->counter, renewal->counter_low);
  const std::uint32_t mac =
      security::frame_mac(*options_.key, security::renewal_mac_input(options_.address, counter, renewable_->counter)) >>
      (32 - reliability::kRenewalMacBits);
  for (const reliability::RenewalSlot& slot : renewal->slots) {
    if (slot.address == options_.address && slot.mac == mac) return counter;
  }
  return std::nullopt;
}

bool FrameAdmission::admit_renewal(Reception& r) {
  const auto counter = renewal_counter(r.bits);
  if (!counter) return false;
  r.answered = false;  // up to three robots heard it: answers would sound together
  r.counter = *counter;
  if (*counter == renewable_->counter) {  // a sender numbers a renewal after the velocity it renews
    refuse(r, RefusalReason::Authentication,
           "a renewal numbered as the velocity it renews (counter " + std::to_string(*counter) + "): forged");
    return true;
  }
  if (take_renewal(r, *counter, "renewal of the velocity of counter " + std::to_string(renewable_->counter),
                   RefusalReason::Authentication))
    r.authenticated = true;
  return true;
}

bool FrameAdmission::take_renewal(Reception& r, std::uint64_t id, const std::string& what, RefusalReason late) {
  if (r.start_ms - renewable_->start_ms > kRenewalHorizonMs) {
    refuse(r, late,
           "a " + what + ", " + std::to_string(static_cast<int>((r.start_ms - renewable_->start_ms) / 1000)) +
               " s after it, past the " + std::to_string(static_cast<int>(kRenewalHorizonMs / 1000)) +
               " s a velocity is renewed for: renewals captured and played later");
    return false;
  }
  if (r.start_ms > renewable_->lease_ends_ms) {
    refuse(r, late,
           "a " + what + ", " + std::to_string(static_cast<int>(r.start_ms - renewable_->lease_ends_ms)) +
               " ms after the velocity's lease ran out: the robot stopped, and only a new velocity frame drives it "
               "again");
    return false;
  }
  if (!renewable_->renewed.insert(id).second) {  // its echo, or played again: renewed already
    r.event = ReceptionEvent::Repeat;
    r.detail = "repeat of " + what + ", not executed again";
    return true;
  }
  echoes_.remember(r.bits, r.heard_ms);
  renewable_->lease_ends_ms = lease_end(renewable_->velocity, r.start_ms);
  r.command = renewable_->velocity;
  r.event = ReceptionEvent::Renewed;
  r.detail = what + ": " + command::describe(*r.command);
  return true;
}

bool FrameAdmission::command_authentic(const reliability::FrameBits& bits) const {
  const auto frame = reliability::sealed_frame_unpack(bits);
  if (!frame || !options_.key) return false;
  const std::uint64_t counter = completed_counter(*frame, options_.counters->last_accepted());
  return security::frame_mac(*options_.key, mac_input(*frame, counter)) == frame->mac;
}

bool FrameAdmission::authentic(const reliability::FrameBits& bits) const {
  const auto frame = reliability::sealed_frame_unpack(bits);
  if (frame && room_authentic(*frame)) return true;
  return command_authentic(bits) || renewal_counter(bits);
}

void FrameAdmission::admit_sealed(Reception& r) {
  const reliability::SealedFrame frame = *reliability::sealed_frame_unpack(r.bits);
  if (!options_.key) {
    refuse_unchecked(r, "an authenticated frame, and this robot has no key (dtmf-agent --key)");
    return;
  }
  security::CounterStore& counters = *options_.counters;
  const std::uint64_t last = counters.last_accepted();
  const std::uint64_t counter = completed_counter(frame, last);
  r.counter = counter;
  if (security::frame_mac(*options_.key, mac_input(frame, counter)) != frame.mac) {
    refuse_unchecked(r, "its MAC fails for counter " + std::to_string(counter) +
                            ": forged, captured before the last frame accepted, or made under another key");
    return;
  }
  switch (security::freshness_of(last, counter)) {
    case security::Freshness::Stale:
      refuse(r, RefusalReason::Authentication,
             "counter " + std::to_string(counter) + " is older than the last accepted, " + std::to_string(last) +
                 ": a frame captured and played again");
      return;
    case security::Freshness::Repeat:
      r.authenticated = true;
      r.event = ReceptionEvent::Repeat;
      r.detail = "repeat of counter " + std::to_string(counter) + ", not executed again";
      return;
    case security::Freshness::New:
      break;
  }
  counters.accept(counter);  // kept before the frame acts or is answered
  r.authenticated = true;
  if (frame.form == reliability::SealedForm::Sync) {
    echoes_.remember(r.bits, r.heard_ms);
    r.event = ReceptionEvent::Synchronised;
    r.detail = "counter synchronised at " + std::to_string(counter);
    return;
  }
  const auto decoded = command::decode_payload(frame.payload);
  if (!decoded.command) {
    refuse(r, RefusalReason::Payload, decoded.error);
    return;
  }
  take_command(r, *decoded.command);
  if (const auto* velocity = std::get_if<command::Velocity>(&*decoded.command))
    renewable_ = Renewable{counter, *velocity, r.start_ms, lease_end(*velocity, r.start_ms), {}, true};
}

void FrameAdmission::take_command(Reception& r, const command::Command& command) {
  renewable_.reset();  // a renewal renews the velocity taken last, and only while nothing came after it
  echoes_.remember(r.bits, r.heard_ms);
  r.command = command;
  r.event = ReceptionEvent::Command;
  r.detail = command::describe(*r.command);
}

}  // namespace dtmf::link
