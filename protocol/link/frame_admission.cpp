#include "link/frame_admission.h"

#include <algorithm>

#include "command/command_payload.h"
#include "link/admission_verdicts.h"
#include "reliability/command_frame.h"
#include "reliability/plain_renewal.h"
#include "reliability/sealed_frame.h"
#include "security/counter_clock.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {

using admission::refuse;
using admission::refuse_unchecked;

// The address a frame's bits name, read even where its check failed (its top three bits).
std::uint8_t address_read(const reliability::FrameBits& bits, int bit_count) {
  return static_cast<std::uint8_t>((bits.value() >> (bit_count - reliability::kAddressBits)) &
                                   reliability::kAddressMask);
}

// The payloads a frame in synchronisation form may stand for, which it does not carry: a
// synchronisation's, and a Stop's (a Stop always carries its whole counter, so that a robot
// out of step can place it: fast_link.cpp).
constexpr std::uint32_t kSyncPayload = 0;
const std::uint32_t kStopPayload = command::encode_payload(command::Stop{});

security::FrameMacInput mac_input(const reliability::SealedFrame& f, std::uint64_t counter, std::uint32_t payload) {
  return {f.address, static_cast<std::uint8_t>(f.form), counter, payload};
}

// The counter a frame stands for, after the last accepted: a synchronisation carries all of
// it, a command its low bits (security/freshness.h).
std::uint64_t completed_counter(const reliability::SealedFrame& f, std::uint64_t last_accepted) {
  return f.form == reliability::SealedForm::Sync
             ? f.counter
             : security::complete_counter(last_accepted, static_cast<std::uint32_t>(f.counter));
}

}  // namespace

std::string admission::ahead_of_clock_words(std::uint64_t counter, std::uint64_t clock_counter) {
  const double ahead_s = static_cast<double>(counter - std::min(counter, clock_counter)) / security::kCountersPerSecond;
  return std::to_string(static_cast<long long>(ahead_s)) +
         " s ahead of this robot's clock (the margin: " + std::to_string(security::kClockMarginS) + " s)";
}

security::FrameMacInput sealed_mac_input(const Reception& r) {
  const auto f = reliability::sealed_frame_unpack(r.bits);
  return f && r.counter ? mac_input(*f, *r.counter, r.mac_payload) : security::FrameMacInput{};
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
    renewable_ =
        Renewable{frame.sequence, *velocity, r.start_ms, admission::lease_end(*velocity, r.start_ms), {}, false};
}

std::optional<std::uint32_t> FrameAdmission::sealed_payload(const reliability::SealedFrame& frame,
                                                            std::uint64_t counter) const {
  if (!options_.key) return std::nullopt;
  const auto holds = [&](std::uint32_t payload) {
    return security::frame_mac(*options_.key, mac_input(frame, counter, payload)) == frame.mac;
  };
  if (frame.form == reliability::SealedForm::Command)
    return holds(frame.payload) ? std::optional(frame.payload) : std::nullopt;
  if (holds(kSyncPayload)) return kSyncPayload;
  if (holds(kStopPayload)) return kStopPayload;
  return std::nullopt;
}

bool FrameAdmission::command_authentic(const reliability::FrameBits& bits) const {
  const auto frame = reliability::sealed_frame_unpack(bits);
  return frame && options_.key && sealed_payload(*frame, completed_counter(*frame, options_.counters->last_accepted()));
}

bool FrameAdmission::authentic(const reliability::FrameBits& bits) const {
  const auto frame = reliability::sealed_frame_unpack(bits);
  if (frame && room_authentic(*frame)) return true;
  return command_authentic(bits) || renewal_counter(bits);
}

std::uint64_t FrameAdmission::clock_counter() const { return security::clock_counter_floor(options_.wall_clock()); }

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
  const auto payload = sealed_payload(frame, counter);
  if (!payload) {
    refuse_unchecked(r, "its MAC fails for counter " + std::to_string(counter) +
                            ": forged, captured before the last frame accepted, or made under another key");
    return;
  }
  r.mac_payload = *payload;
  const bool synchronisation = frame.form == reliability::SealedForm::Sync && *payload == kSyncPayload;
  const auto decoded = command::decode_payload(*payload);
  const std::uint64_t clock = clock_counter();
  switch (security::freshness_of(last, counter, clock)) {
    case security::Freshness::Ahead:
      if (!synchronisation && decoded.command && std::holds_alternative<command::Stop>(*decoded.command)) {
        take_stop_ahead(r, *decoded.command, clock);  // a stop is never refused for its time
        return;
      }
      refuse(r, RefusalReason::Authentication,
             "counter " + std::to_string(counter) + " lies " + admission::ahead_of_clock_words(counter, clock) +
                 ": not taken nor kept. Is the sender's clock fast, or this robot's slow? Set both by NTP");
      return;
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
  if (synchronisation) {
    echoes_.remember(r.bits, r.heard_ms);
    r.event = ReceptionEvent::Synchronised;
    r.detail = "counter synchronised at " + std::to_string(counter);
    return;
  }
  if (!decoded.command) {
    refuse(r, RefusalReason::Payload, decoded.error);
    return;
  }
  take_command(r, *decoded.command);
  if (frame.form == reliability::SealedForm::Sync) r.detail += " (its whole counter carried: in step from here)";
  if (const auto* velocity = std::get_if<command::Velocity>(&*decoded.command))
    renewable_ = Renewable{counter, *velocity, r.start_ms, admission::lease_end(*velocity, r.start_ms), {}, true};
}

// A Stop whose counter lies past this robot's clock: a sender whose clock runs fast (or this
// robot's slow). Refusing it would leave the robot driving; its counter is not kept, so it
// cannot make the true frames after it look old.
void FrameAdmission::take_stop_ahead(Reception& r, const command::Command& stop, std::uint64_t clock) {
  r.authenticated = true;
  take_command(r, stop);
  r.detail += "; counter " + std::to_string(*r.counter) + " lies " +
              admission::ahead_of_clock_words(*r.counter, clock) +
              ": stopped, the counter not kept (is the sender's clock fast, or this robot's slow?)";
}

void FrameAdmission::take_command(Reception& r, const command::Command& command) {
  renewable_.reset();  // a renewal renews the velocity taken last, and only while nothing came after it
  echoes_.remember(r.bits, r.heard_ms);
  r.command = command;
  r.event = ReceptionEvent::Command;
  r.detail = command::describe(*r.command);
}

}  // namespace dtmf::link
