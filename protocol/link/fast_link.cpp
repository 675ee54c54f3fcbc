// The `fast` profile's link (HopPlan): address, a number and the 27-bit
// command, checked by a CRC (and with a key authenticated by a MAC over a freshness
// counter), as a Reed-Solomon codeword of hopped 32-ary tones; ACK / NACK replies below the
// chords, and the ACK to an authenticated frame one chord spelling its tag in the frame bands.
// Here: numbering commands, and the robot's and the ear's paths. How each frame sounds is
// fast_frames.cpp; joint renewals are planned by renewal_planner.cpp from the record kept here.
#include "link/fast_link.h"

#include <algorithm>
#include <random>

#include "command/command_payload.h"
#include "command/random_command.h"
#include "link/fast_answer_listener.h"
#include "link/fast_frames.h"
#include "link/frame_admission.h"
#include "link/hop_frame_path.h"
#include "link/reply_lane.h"
#include "reliability/command_frame.h"
#include "reliability/reply_code.h"
#include "reliability/sealed_frame.h"
#include "security/freshness.h"
#include "signal/hop_reply.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {

// Offline recordings leave each frame the time its answer takes, as a sender would.
constexpr double kAnswerWaitMs = 100;

class FastReceiver final : public FrameReceiver {
 public:
  FastReceiver(const LinkProfile& profile, const LinkOptions& options)
      : admission_(profile, options),
        path_(profile,
              options.key || options.room_key ? reliability::SealedCheck([this](const reliability::FrameBits& bits) {
                return admission_.authentic(bits);
              })
                                              : reliability::SealedCheck(),
              !options.key || options.accept_unauthenticated) {}
  std::span<const Reception> feed(std::span<const float> samples) override {
    receptions_.clear();
    for (const HeardHopFrame& heard : path_.feed(samples)) {
      if (auto r = admission_.admit(heard)) receptions_.push_back(std::move(*r));
    }
    return receptions_;
  }
  std::size_t echoes_ignored() const override { return admission_.echoes_ignored(); }

 private:
  FrameAdmission admission_;
  HopFramePath path_;
  std::vector<Reception> receptions_;
};

}  // namespace

FastLink::FastLink(const LinkProfile& profile, LinkOptions options)
    : Link(profile, std::move(options)),
      next_sequence_(options_.first_sequence.value_or(static_cast<std::uint8_t>(std::random_device{}()))) {}

TransmitFrame FastLink::plain_frame(std::uint32_t payload) {
  const reliability::CommandFrame frame{
      options_.address, static_cast<std::uint8_t>(next_sequence_ & reliability::kSequenceMask), payload};
  next_sequence_ = static_cast<std::uint8_t>((frame.sequence + 1) & reliability::kSequenceMask);
  return command_transmit_frame(profile(), frame);
}

TransmitFrame FastLink::sealed_frame(std::uint32_t payload, bool synchronisation, std::uint64_t counter) const {
  return sealed_transmit_frame(profile(), *options_.key, {options_.address, payload, synchronisation, counter});
}

std::vector<TransmitFrame> FastLink::broadcast_frames(std::uint32_t payload) {
  std::vector<TransmitFrame> frames;
  for (int copy = 0; copy < profile().timing.broadcast_copies; ++copy) {
    // Sealed, it carries its whole counter: room counters come from several senders and
    // name times (security/room_freshness.h), so no robot could complete low bits.
    TransmitFrame f = keyed() ? sealed_frame(payload, true, options_.counters->next_counter()) : plain_frame(payload);
    f.synchronisation = false;
    f.broadcast = true;
    f.next_frame_after_ms = f.tone_ms + profile().timing.gap_ms;  // no answer to wait for
    frames.push_back(std::move(f));
  }
  return frames;
}

std::vector<TransmitFrame> FastLink::plan(const command::Command& command) {
  const std::uint32_t payload = command::encode_payload(command);  // throws before a counter is used
  if (command::every_robot(command)) return broadcast_frames(payload);
  renewal_.velocity_counter.reset();
  renewal_.velocity_sequence.reset();
  if (!keyed()) {
    TransmitFrame f = plain_frame(payload);
    if (std::holds_alternative<command::Velocity>(command)) renewal_.velocity_sequence = f.sequence;
    return {std::move(f)};
  }
  std::vector<TransmitFrame> frames;
  security::CounterStore& counters = *options_.counters;
  std::uint64_t counter = counters.next_counter();
  if (std::holds_alternative<command::Stop>(command)) {
    // A Stop carries its whole counter, its MAC over STOP: a robot out of step places it with
    // no synchronisation first, so no unanswered synchronisation can keep it off the air, and
    // it costs no extra frame (docs/protocol.md §10, "A Stop carries its counter").
    TransmitFrame stop = sealed_frame(payload, true, counter);
    stop.synchronisation = false;
    return {std::move(stop)};
  }
  if (!security::completable(counters.last_confirmed(), counter)) {
    frames.push_back(sealed_frame(0, true, counter));
    counter = counters.next_counter();
  }
  frames.push_back(sealed_frame(payload, false, counter));
  if (std::holds_alternative<command::Velocity>(command)) renewal_.velocity_counter = counter;
  return frames;
}

std::size_t FastLink::frame_count(const command::Command& command) const {
  command::encode_payload(command);  // throws for what no frame can carry
  if (command::every_robot(command)) return static_cast<std::size_t>(profile().timing.broadcast_copies);
  return 1;
}

command::Command FastLink::as_received(const command::Command& command) const {
  return command::quantised_payload(command);
}

int FastLink::payload_bits(const command::Command&) const { return command::kPayloadBits; }

// A random valid command (the robot refuses payloads no sender makes), numbered as plan()
// numbers it but never preceded by a synchronisation: a benchmark's robot starts in step.
TransmitFrame FastLink::random_frame(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::uint32_t payload = command::encode_payload(command::random_command(rng));
  // Numbered on, as a sender numbers its frames: random numbers would repeat one of the last
  // 15 frames now and then, which the robot takes for an echo (reliability/echo_memory.h).
  if (!keyed()) return plain_frame(payload);
  return sealed_frame(payload, false, options_.counters->next_counter());
}

double FastLink::frame_start_ms(std::size_t index) const {
  const int samples = keyed() ? profile().hops().sealed_frame_samples() : profile().hops().frame_samples();
  const double frame_ms = 1000.0 * samples / profile().sample_rate_hz;
  return static_cast<double>(index) * (frame_ms + kAnswerWaitMs);
}

void FastLink::confirmed(const TransmitFrame& frame) {
  if (frame.counter && options_.counters) options_.counters->confirmed(*frame.counter);
}

std::unique_ptr<FrameReceiver> FastLink::receiver() const {
  return std::make_unique<FastReceiver>(profile(), options_);
}

std::vector<float> FastLink::answer_audio(const Reception& r) const {
  if (!r.answered) return {};
  if (r.acknowledged() && r.counter && options_.key) {
    const auto input = sealed_mac_input(r);
    const std::uint32_t mac = reliability::sealed_frame_unpack(r.bits)->mac;
    const double frame_end_ms =
        r.start_ms + 1000.0 * profile().hops().sealed_frame_samples() / profile().sample_rate_hz;
    std::vector<float> audio(static_cast<std::size_t>(profile().samples_for_ms(
                                 std::max(0.0, frame_end_ms + profile().hops().tag_after_frame_ms - r.heard_ms))),
                             0.0f);
    const std::vector<float> chord = signal::synthesize_tag_chord(
        profile(),
        reply_tag(*options_.key, input, mac, reliability::tag_chord_taken(reliability::sealed_frame_symbols(r.bits))));
    audio.insert(audio.end(), chord.begin(), chord.end());
    return audio;
  }
  // (The robot answers only frames for its own address: FrameAdmission.)
  if (r.acknowledged()) {
    return signal::synthesize_hopped_reply(
        profile(), reliability::reply_codeword({true, r.sequence.value_or(0), options_.address}),
        answer_lane(r.sequence.value_or(0)));
  }
  return signal::synthesize_hopped_reply(profile(), reliability::reply_codeword({false, 0, options_.address}),
                                         kNackLane);
}

int FastLink::receiver_block_samples() const { return profile().hops().hop_samples; }

std::unique_ptr<AnswerListener> FastLink::answer_listener() const {
  return std::make_unique<FastAnswerListener>(profile(), keyed());
}

int FastLink::answer_block_samples() const { return profile().hops().reply_hop_samples; }

bool FastLink::answers(const Answer& answer, const TransmitFrame& frame) const {
  // Only the robot the frame is for: a NACK answers whatever frame of its robot is on air.
  if (!answer.tag_reading && answer.address != frame.address) return false;
  if (!answer.ack) return true;
  if (frame.authenticated)
    return answer.tag_reading && reliability::spells_tag_chord(*answer.tag_reading, frame.answer_tag, frame.sent_tones);
  if (answer.lane != frame.answer_lane) return false;
  return answer.sequence && answer.sequence == frame.sequence;
}

}  // namespace dtmf::link
