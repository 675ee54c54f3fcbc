// The `fast` profile's link (FrameFormat::HoppedCommand): address, sequence number, 27-bit
// command and CRC-16 as a Reed-Solomon codeword of sixteen hopped 32-ary tones; ACK(sequence)
// / NACK replies below the chords.
#include "link/fast_link.h"

#include <random>

#include "command/command_payload.h"
#include "command/random_command.h"
#include "link/hop_frame_path.h"
#include "reliability/command_frame.h"
#include "reliability/reply_code.h"
#include "signal/hop_reply.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {

// Offline recordings leave each frame the time its answer takes, as a sender would.
constexpr double kAnswerWaitMs = 100;
constexpr int kNackId = 16;  // the listener's id for a NACK (ACKs are their sequence numbers)

class FastReceiver final : public FrameReceiver {
 public:
  explicit FastReceiver(const LinkProfile& profile) : profile_(profile), path_(profile) {}
  std::span<const Reception> feed(std::span<const float> samples) override {
    receptions_.clear();
    for (const ReceivedHopFrame& f : path_.feed(samples)) {
      Reception r;
      r.start_ms = f.start_ms;
      r.heard_ms = f.heard_ms;
      r.bits = f.bits;
      r.bit_count = reliability::kCommandFrameBits;
      r.check_bit_count = reliability::kCommandCrcBits;
      r.intact = f.frame.has_value();
      const auto tones = signal::frame_tones_hz(profile_, reliability::encode_symbols(f.bits));
      r.tones_hz.assign(tones.begin(), tones.end());
      if (f.frame) {
        r.sequence = f.frame->sequence;
        r.event = f.repeat ? "repeat" : "command";
        r.command = f.command;
        r.detail = f.command ? command::describe(*f.command) : "repeat, not executed again";
      } else if (!f.error.empty()) {
        r.event = "refused";
        r.detail = f.error;
      }
      receptions_.push_back(std::move(r));
    }
    return receptions_;
  }

 private:
  const LinkProfile& profile_;
  HopFramePath path_;
  std::vector<Reception> receptions_;
};

class FastAnswerListener final : public AnswerListener {
 public:
  explicit FastAnswerListener(const LinkProfile& profile)
      : listener_(profile, [needed = profile.hops.reply_bands_needed](const std::array<int, 4>& tones) {
          const auto reply = reliability::read_reply(tones, needed);
          return reply ? (reply->ack ? reply->sequence : kNackId) : -1;
        }) {}
  std::span<const Answer> feed(std::span<const float> samples) override {
    answers_.clear();
    for (const signal::HeardReply& h : listener_.feed(samples)) {
      const bool ack = h.reply != kNackId;
      answers_.push_back({ack, ack ? std::optional(static_cast<std::uint8_t>(h.reply)) : std::nullopt, h.heard_ms});
    }
    return answers_;
  }

 private:
  signal::HopReplyListener listener_;
  std::vector<Answer> answers_;
};

}  // namespace

std::vector<TransmitFrame> FastLink::plan(const command::Command& command, std::uint8_t& next_sequence) const {
  const reliability::CommandFrame frame{0, static_cast<std::uint8_t>(next_sequence & reliability::kSequenceMask),
                                        command::encode_payload(command)};
  next_sequence = static_cast<std::uint8_t>((frame.sequence + 1) & reliability::kSequenceMask);
  TransmitFrame f;
  f.bits = reliability::pack(frame);
  f.bit_count = reliability::kCommandFrameBits;
  f.check_bit_count = reliability::kCommandCrcBits;
  f.sequence = frame.sequence;
  const reliability::CodeSymbols symbols = reliability::encode_symbols(f.bits);
  const auto tones = signal::frame_tones_hz(profile(), symbols);
  f.tones_hz.assign(tones.begin(), tones.end());
  f.audio = signal::synthesize_hopped_frame(profile(), symbols);
  f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile().sample_rate_hz;
  return {std::move(f)};
}

command::Command FastLink::as_received(const command::Command& command) const {
  return command::quantised_payload(command);
}

int FastLink::payload_bits(const command::Command&) const { return command::kPayloadBits; }

// A random valid command under a random number: the robot refuses payloads no sender makes.
TransmitFrame FastLink::random_frame(std::uint64_t seed) const {
  std::mt19937_64 rng(seed);
  const command::Command c = command::random_command(rng);
  auto sequence = static_cast<std::uint8_t>(rng());
  return plan(c, sequence).front();
}

double FastLink::frame_start_ms(std::size_t index) const {
  const double frame_ms = 1000.0 * profile().hops.frame_samples() / profile().sample_rate_hz;
  return static_cast<double>(index) * (frame_ms + kAnswerWaitMs);
}

std::unique_ptr<FrameReceiver> FastLink::receiver() const { return std::make_unique<FastReceiver>(profile()); }

std::vector<float> FastLink::answer_audio(const Reception& reception) const {
  const bool ack = reception.intact;
  const reliability::NamedReply reply{ack, ack ? reception.sequence.value_or(0) : std::uint8_t{0}};
  return signal::synthesize_hopped_reply(profile(), reliability::reply_codeword(reply));
}

int FastLink::receiver_block_samples() const { return profile().hops.hop_samples; }

std::unique_ptr<AnswerListener> FastLink::answer_listener() const {
  return std::make_unique<FastAnswerListener>(profile());
}

int FastLink::answer_block_samples() const { return profile().hops.reply_hop_samples; }

bool FastLink::answers(const Answer& answer, const TransmitFrame& frame) const {
  return !answer.ack || answer.sequence == frame.sequence;
}

}  // namespace dtmf::link
