// The `fast` profile's link (HopPlan): address, a number and the 27-bit
// command, checked by a CRC (and with a key authenticated by a MAC over a freshness
// counter), as a Reed-Solomon codeword of hopped 32-ary tones; ACK / NACK replies below the
// chords, and the ACK to an authenticated frame one chord spelling its tag in the frame bands.
#include "link/fast_link.h"

#include <algorithm>
#include <random>

#include "command/command_payload.h"
#include "command/random_command.h"
#include "link/fast_answer_listener.h"
#include "link/frame_admission.h"
#include "link/hop_frame_path.h"
#include "link/reply_lane.h"
#include "reliability/command_frame.h"
#include "reliability/plain_renewal.h"
#include "reliability/renewal_frame.h"
#include "reliability/reply_code.h"
#include "reliability/sealed_frame.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "signal/hop_reply.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {

// Offline recordings leave each frame the time its answer takes, as a sender would.
constexpr double kAnswerWaitMs = 100;

static_assert(security::kAnswerTagBytes == reliability::kTagBytes);

// The tag the ACK to an authenticated frame spells, as its chord's symbols, in the bins the
// frame left free.
reliability::TagChordSymbols reply_tag(const security::LinkKey& key, const security::FrameMacInput& input,
                                       std::uint32_t mac, const reliability::BandValueSet& taken) {
  return reliability::tag_chord_symbols(security::answer_tag(key, input, mac), taken);
}

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
  return frame_of(frame);
}

TransmitFrame FastLink::frame_of(const reliability::CommandFrame& frame) const {
  TransmitFrame f;
  f.bits = reliability::command_frame_pack(frame);
  f.bit_count = reliability::kCommandFrameBits;
  f.check_bit_count = reliability::kCommandCrcBits;
  f.sequence = frame.sequence;
  f.address = frame.address;
  f.answer_lane = answer_lane(frame.sequence);
  const auto symbols = reliability::command_frame_symbols(f.bits.low64());
  f.tones_hz = signal::frame_tones_hz(profile(), symbols);
  f.audio = signal::synthesize_hopped_frame(profile(), symbols);
  f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile().sample_rate_hz;
  f.next_frame_after_ms = f.tone_ms + profile().timing.gap_ms;  // its answer sounds in the reply bands
  return f;
}

TransmitFrame FastLink::sealed_frame(std::uint32_t payload, bool synchronisation, std::uint64_t counter) const {
  const auto form = synchronisation ? reliability::SealedForm::Sync : reliability::SealedForm::Command;
  const security::FrameMacInput input{options_.address, static_cast<std::uint8_t>(form), counter, payload};
  reliability::SealedFrame frame;
  frame.address = options_.address;
  frame.form = form;
  frame.counter = synchronisation ? counter : security::counter_low_bits(counter);
  frame.payload = payload;
  frame.mac = security::frame_mac(*options_.key, input);
  TransmitFrame f;
  f.bits = reliability::sealed_frame_pack(frame);
  f.bit_count = reliability::kSealedFrameBits;
  f.check_bit_count = reliability::kSealedCheckBits;
  f.address = frame.address;
  f.authenticated = true;
  f.synchronisation = synchronisation;
  f.counter = counter;
  f.answer_lane = answer_lane(counter);
  const auto symbols = reliability::sealed_frame_symbols(f.bits);
  f.sent_tones = reliability::tag_chord_taken(symbols);
  f.answer_tag = reply_tag(*options_.key, input, frame.mac, f.sent_tones);
  f.tones_hz = signal::frame_tones_hz(profile(), symbols);
  f.audio = signal::synthesize_hopped_frame(profile(), symbols);
  f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile().sample_rate_hz;
  f.next_frame_after_ms =
      std::max(f.tone_ms + profile().timing.gap_ms, profile().hops().sealed_bands_busy_ms(profile().sample_rate_hz));
  return f;
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
  velocity_counter_.reset();
  velocity_sequence_.reset();
  if (!keyed()) {
    TransmitFrame f = plain_frame(payload);
    if (std::holds_alternative<command::Velocity>(command)) velocity_sequence_ = f.sequence;
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
  if (std::holds_alternative<command::Velocity>(command)) velocity_counter_ = counter;
  return frames;
}

std::vector<std::size_t> FastLink::renewable(std::span<Link* const> robots) const {
  // Links of this profile, keyed as this one is, whose last frame planned was a velocity.
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < robots.size() && candidates.size() < reliability::kRenewalSlots; ++i) {
    const auto* link = dynamic_cast<const FastLink*>(robots[i]);
    if (link && &link->profile() == &profile() && link->keyed() == keyed() &&
        (keyed() ? link->velocity_counter_.has_value() : link->velocity_sequence_.has_value()))
      candidates.push_back(i);
  }
  return candidates;
}

std::optional<Link::PlannedRenewal> FastLink::plan_renewal(std::span<Link* const> robots) {
  const std::vector<std::size_t> candidates = renewable(robots);
  if (candidates.empty()) return std::nullopt;
  if (!keyed()) return plan_plain_renewal(robots, candidates);
  // One counter, new to every one of them.
  std::uint64_t counter = 0;
  for (const std::size_t i : candidates) counter = std::max(counter, robots[i]->options().counters->next_counter());
  PlannedRenewal planned;
  reliability::RenewalFrame renewal;
  renewal.counter_low = security::counter_low_bits(counter);
  for (const std::size_t i : candidates) {
    auto& link = static_cast<FastLink&>(*robots[i]);
    security::CounterStore& counters = *link.options().counters;
    counters.next_counter_from(counter);  // used here, whether or not its robot can take it
    // The robot completes the low bits from its velocity frame's counter: one that could not
    // is left out, and its next frame, numbered after this one, is in step again.
    if (counter - *link.velocity_counter_ >= security::kCounterWindow) continue;
    const std::uint8_t address = link.options().address;
    const std::uint32_t mac = security::frame_mac(
        *link.options().key, security::renewal_mac_input(address, counter, *link.velocity_counter_));
    renewal.slots[planned.renewed.size()] = {address, mac >> (32 - reliability::kRenewalMacBits)};
    planned.renewed.push_back(i);
  }
  if (planned.renewed.empty()) return std::nullopt;
  // Slots nobody fills repeat the first: a robot checks the same slot twice, no other robot's.
  for (std::size_t slot = planned.renewed.size(); slot < renewal.slots.size(); ++slot)
    renewal.slots[slot] = renewal.slots[0];
  TransmitFrame& f = planned.frame;
  f.bits = reliability::renewal_frame_pack(renewal);
  f.bit_count = reliability::kSealedFrameBits;
  f.check_bit_count = reliability::kSealedCheckBits;
  f.address = renewal.slots[0].address;
  f.authenticated = true;
  f.renewal = true;
  f.counter = counter;
  const auto symbols = reliability::sealed_frame_symbols(f.bits);
  f.tones_hz = signal::frame_tones_hz(profile(), symbols);
  f.audio = signal::synthesize_hopped_frame(profile(), symbols);
  f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile().sample_rate_hz;
  f.next_frame_after_ms = f.tone_ms + profile().timing.gap_ms;  // no answer to wait for
  return planned;
}

std::optional<Link::PlannedRenewal> FastLink::plan_plain_renewal(std::span<Link* const> robots,
                                                                 const std::vector<std::size_t>& candidates) {
  // One number, new to every one of them: each robot takes a renewal's number once.
  std::uint64_t number = 0;
  for (const std::size_t i : candidates)
    number = std::max(number, static_cast<FastLink&>(*robots[i]).next_renewal_number_);
  PlannedRenewal planned;
  reliability::PlainRenewal renewal;
  renewal.number = static_cast<std::uint32_t>(number & reliability::kPlainRenewalNumberMask);
  for (const std::size_t i : candidates) {
    auto& link = static_cast<FastLink&>(*robots[i]);
    link.next_renewal_number_ = number + 1;
    renewal.slots[planned.renewed.size()] = {link.options().address, *link.velocity_sequence_};
    planned.renewed.push_back(i);
  }
  for (std::size_t slot = planned.renewed.size(); slot < renewal.slots.size(); ++slot)
    renewal.slots[slot] = renewal.slots[0];
  TransmitFrame& f = planned.frame;
  f = frame_of(reliability::plain_renewal_pack(renewal));
  f.sequence.reset();  // no answer names it
  f.address = renewal.slots[0].address;
  f.renewal = true;
  return planned;
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
