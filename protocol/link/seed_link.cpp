// The `seed` profile's link (Word16): RESET / mode / parameter words, one CRC-4 frame and one
// four-tone chord each; the robot's word state machine; ACK / NACK chords any frame accepts.
#include "link/seed_link.h"

#include <random>

#include "command/word_codec.h"
#include "link/seed_receiver_path.h"
#include "link/seed_sender_path.h"
#include "reliability/crc4.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"

namespace dtmf::link {

namespace {

std::string event_detail(const command::ReceiverEvent& event) {
  using Kind = command::ReceiverEvent::Kind;
  switch (event.kind) {
    case Kind::Reset:
      return "reset -> mode_select";
    case Kind::ModeSelected:
      return "mode " + command::mode_name(*event.mode);
    case Kind::CommandReady:
      return "command " + command::describe(*event.command);
    case Kind::Ignored:
      return "ignored: " + event.reason;
  }
  return "";
}

ReceptionEvent event_of(command::ReceiverEvent::Kind kind) {
  using Kind = command::ReceiverEvent::Kind;
  switch (kind) {
    case Kind::Reset:
      return ReceptionEvent::Reset;
    case Kind::ModeSelected:
      return ReceptionEvent::ModeSelected;
    case Kind::CommandReady:
      return ReceptionEvent::Command;
    case Kind::Ignored:
      return ReceptionEvent::Ignored;
  }
  return ReceptionEvent::Ignored;
}

class SeedReceiver final : public FrameReceiver {
 public:
  SeedReceiver(const LinkProfile& profile, bool refuse_all)
      : profile_(profile), refuse_(refuse_all), path_(profile, !refuse_all) {}
  std::span<const Reception> feed(std::span<const float> samples) override {
    receptions_.clear();
    for (const SeedReceivedFrame& f : path_.feed(samples)) {
      Reception r;
      r.start_ms = f.start_ms;
      r.heard_ms = f.heard_ms;
      r.bits = f.frame;
      r.bit_count = reliability::kSeedFrameBits;
      r.check_bit_count = reliability::kCrcBits;
      r.intact = f.crc_ok;
      const signal::Chord chord = signal::chord_for(profile_.words().tones, f.frame);
      r.tones_hz.assign(chord.begin(), chord.end());
      if (f.crc_ok) r.payload_word = reliability::word_frame_word(f.frame);
      if (f.crc_ok && refuse_) {
        r.event = ReceptionEvent::Refused;
        r.refusal = RefusalReason::Authentication;
        r.detail =
            "a seed frame cannot carry a MAC, and this robot has a key (dtmf-agent --accept-unauthenticated lets "
            "them in)";
      } else if (f.event) {
        r.event = event_of(f.event->kind);
        r.command_state = command::state_name(f.event->state_after);
        r.command = f.event->command;
        r.detail = event_detail(*f.event);
      }
      receptions_.push_back(std::move(r));
    }
    return receptions_;
  }

 private:
  const LinkProfile& profile_;
  bool refuse_;
  SeedReceiverPath path_;
  std::vector<Reception> receptions_;
};

class SeedAnswerListener final : public AnswerListener {
 public:
  explicit SeedAnswerListener(const LinkProfile& profile) : listener_(signal::reply_listener(profile)) {}
  std::span<const Answer> feed(std::span<const float> samples) override {
    answers_.clear();
    for (const signal::Heard& h : listener_.feed(samples)) {
      answers_.push_back(
          {static_cast<signal::Reply>(h.symbol) == signal::Reply::Ack, std::nullopt, std::nullopt, h.heard_ms});
    }
    return answers_;
  }

 private:
  signal::ToneListener listener_;
  std::vector<Answer> answers_;
};

}  // namespace

TransmitFrame SeedLink::transmit_frame(const SeedPlannedFrame& planned) const {
  TransmitFrame f;
  f.word = planned.word;
  f.bits = planned.frame;
  f.bit_count = reliability::kSeedFrameBits;
  f.check_bit_count = reliability::kCrcBits;
  f.tones_hz.assign(planned.tones_hz.begin(), planned.tones_hz.end());
  f.audio = signal::synthesize_chord(profile(), planned.tones_hz, profile().timing.chord_ms);
  f.tone_ms = profile().timing.chord_ms;
  f.next_frame_after_ms = f.tone_ms + profile().timing.gap_ms;
  return f;
}

std::vector<TransmitFrame> SeedLink::plan(const command::Command& command) {
  std::vector<TransmitFrame> frames;
  for (const SeedPlannedFrame& planned : plan_command(profile(), command)) frames.push_back(transmit_frame(planned));
  return frames;
}

std::size_t SeedLink::frame_count(const command::Command& command) const {
  return plan_command(profile(), command).size();
}

std::optional<TransmitFrame> SeedLink::plan_payload_word(std::uint32_t word) const {
  return transmit_frame(link::plan_word(profile(), static_cast<command::Word>(word)));
}

command::Command SeedLink::as_received(const command::Command& command) const { return command::quantised(command); }

int SeedLink::payload_bits(const command::Command& command) const {
  return static_cast<int>(plan_command(profile(), command).size()) *
         (reliability::kSeedFrameBits - reliability::kCrcBits);
}

// Any of the 4096 words, not just the commands': the CRC and the tone plan see them all.
TransmitFrame SeedLink::random_frame(std::uint64_t seed) {
  return transmit_frame(
      link::plan_word(profile(), static_cast<command::Word>(std::mt19937_64(seed)() & command::kWordMask)));
}

double SeedLink::frame_start_ms(std::size_t index) const { return link::frame_start_ms(profile(), index); }

std::unique_ptr<FrameReceiver> SeedLink::receiver() const {
  return std::make_unique<SeedReceiver>(profile(), keyed() && !options_.accept_unauthenticated);
}

std::vector<float> SeedLink::answer_audio(const Reception& reception) const {
  return signal::synthesize_reply(profile(), reception.acknowledged() ? signal::Reply::Ack : signal::Reply::Nack);
}

int SeedLink::receiver_block_samples() const { return profile().hop_samples(); }

std::unique_ptr<AnswerListener> SeedLink::answer_listener() const {
  return std::make_unique<SeedAnswerListener>(profile());
}

int SeedLink::answer_block_samples() const { return profile().hop_samples(); }

bool SeedLink::answers(const Answer&, const TransmitFrame&) const { return true; }

}  // namespace dtmf::link
