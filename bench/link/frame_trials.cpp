#include "link/frame_trials.h"

#include <algorithm>
#include <stdexcept>

#include "command/command.h"
#include "link/sender_path.h"
#include "reliability/command_frame.h"
#include "reliability/crc4.h"
#include "signal/bin_synthesizer.h"
#include "signal/synthesizer.h"

namespace dtmf::bench {

namespace {
bool command48(const LinkProfile& profile) { return profile.frame_format == FrameFormat::Command48; }
}  // namespace

FrameReceiver::FrameReceiver(const LinkProfile& profile) {
  if (command48(profile)) commands_ = std::make_unique<link::CommandFramePath>(profile);
  else words_ = std::make_unique<link::ReceiverPath>(profile);
}

ReplyReceiver::ReplyReceiver(const LinkProfile& profile) {
  if (command48(profile)) named_ = std::make_unique<signal::BinReplyListener>(profile);
  else replies_.reset(new signal::ToneListener(signal::reply_listener(profile)));  // not movable: built in place
}

void ReplyReceiver::feed(std::span<const float> samples) {
  if (named_) {
    for (const signal::HeardReply& h : named_->feed(samples)) (h.reply.ack ? acks_ : nacks_)++;
    return;
  }
  for (const signal::Heard& h : replies_->feed(samples)) {
    (static_cast<signal::Reply>(h.symbol) == signal::Reply::Ack ? acks_ : nacks_)++;
  }
}

void FrameReceiver::feed(std::span<const float> samples, std::vector<Accepted>& accepted) {
  if (commands_) {
    // A repeat (same sequence number and bits as the last) is accepted and answered too;
    // only its execution is skipped.
    for (const link::ReceivedCommandFrame& r : commands_->feed(samples)) {
      if (r.frame) accepted.push_back({r.start_ms, r.bits});
      else ++check_failed_;
    }
    return;
  }
  for (const link::ReceivedFrame& frame : words_->feed(samples)) {
    if (frame.crc_ok) accepted.push_back({frame.start_ms, frame.frame});
    else ++check_failed_;
  }
}

FrameTrials::FrameTrials(const LinkProfile& profile)
    : profile_(profile),
      slot_samples_(command48(profile) ? static_cast<std::size_t>(profile.bins.frame_samples())
                                       : static_cast<std::size_t>(profile.samples_for_ms(profile.timing.chord_ms + profile.timing.gap_ms))),
      sound_samples_(command48(profile) ? slot_samples_
                                        : static_cast<std::size_t>(profile.samples_for_ms(profile.timing.chord_ms))) {
  if (command48(profile_)) return;  // rendered by the link layer itself, no shortcut to check
  // The shortcut must not change a single sample: compare with the link layer's own rendering.
  std::mt19937_64 rng(12345);
  for (int i = 0; i < 3; ++i) {
    const FrameBits bits = random_frame(rng);
    const std::vector<float> reference =
        link::render_frames(profile_, {link::plan_word(profile_, reliability::frame_word(static_cast<reliability::Frame>(bits)))});
    std::vector<float> ours(reference.size(), 0.0f);
    add_frame(bits, ours);
    if (ours != reference) throw std::logic_error("frame_trials: cached rendering differs from link::render_frames");
  }
}

std::vector<Transmission> command_transmissions(const LinkProfile& profile, const command::Command& command,
                                                std::uint8_t& next_sequence) {
  std::vector<Transmission> out;
  if (command48(profile)) {
    const auto planned = link::plan_command_frame(command, next_sequence);
    next_sequence = static_cast<std::uint8_t>((planned.frame.sequence + 1) & reliability::kSequenceMask);
    out.push_back({link::render_command_frame(profile, planned), planned.frame.sequence});
    return out;
  }
  for (const link::PlannedFrame& f : link::plan_command(profile, command)) {
    out.push_back({signal::synthesize_chord(profile, f.tones_hz, profile.timing.chord_ms), std::nullopt});
  }
  return out;
}

int command_payload_bits(const LinkProfile& profile, const command::Command& command) {
  if (command48(profile)) return reliability::kPayloadBits;
  return static_cast<int>(link::plan_command(profile, command).size()) * (reliability::kFrameBits - reliability::kCrcBits);
}

Responder::Responder(const LinkProfile& profile) : profile_(profile) {
  if (command48(profile)) commands_ = std::make_unique<link::CommandFramePath>(profile);
  else words_ = std::make_unique<link::ReceiverPath>(profile);
}

std::vector<std::vector<float>> Responder::feed(std::span<const float> samples) {
  std::vector<std::vector<float>> answers;
  if (commands_) {
    for (const link::ReceivedCommandFrame& r : commands_->feed(samples)) {
      const signal::NamedReply reply = r.frame ? signal::NamedReply{true, r.frame->sequence} : signal::NamedReply{false, 0};
      answers.push_back(signal::synthesize_named_reply(profile_, reply));
    }
    return answers;
  }
  for (const link::ReceivedFrame& f : words_->feed(samples)) {
    answers.push_back(signal::synthesize_reply(profile_, f.crc_ok ? signal::Reply::Ack : signal::Reply::Nack));
  }
  return answers;
}

AnswerListener::AnswerListener(const LinkProfile& profile) {
  if (command48(profile)) named_ = std::make_unique<signal::BinReplyListener>(profile);
  else replies_.reset(new signal::ToneListener(signal::reply_listener(profile)));  // not movable: built in place
}

std::vector<Answer> AnswerListener::feed(std::span<const float> samples) {
  std::vector<Answer> answers;
  if (named_) {
    for (const signal::HeardReply& h : named_->feed(samples)) {
      answers.push_back({h.reply.ack, h.reply.ack ? std::optional<std::uint8_t>(h.reply.sequence) : std::nullopt});
    }
    return answers;
  }
  for (const signal::Heard& h : replies_->feed(samples)) {
    answers.push_back({static_cast<signal::Reply>(h.symbol) == signal::Reply::Ack, std::nullopt});
  }
  return answers;
}

int frame_data_bits(const LinkProfile& profile) {
  return command48(profile) ? reliability::kPayloadBits : reliability::kFrameBits - reliability::kCrcBits;
}

int FrameTrials::data_bits() const { return frame_data_bits(profile_); }
int FrameTrials::check_bits() const {
  return command48(profile_) ? reliability::kCommandCrcBits : reliability::kCrcBits;
}

namespace {
// A random valid command: every kind, parameters drawn over their whole ranges.
command::Command random_command(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(rng() % 100001) / 100000.0; };
  switch (rng() % 6) {
    case 0: return command::Reset{};
    case 1: return command::Stop{};
    case 2: return command::DriveForDuration{uniform(0, 100), uniform(0, 8)};
    case 3: return command::TurnForDuration{uniform(-100, 100), uniform(0, 8)};
    case 4: return command::DriveForward{uniform(0, 100)};
    default: return command::Turn{uniform(-100, 100)};
  }
}
}  // namespace

FrameBits FrameTrials::random_frame(std::mt19937_64& rng) const {
  if (command48(profile_)) {
    const command::Command c = random_command(rng);
    return link::plan_command_frame(c, static_cast<std::uint8_t>(rng() & reliability::kSequenceMask)).bits;
  }
  const auto word = static_cast<command::Word>(rng() & command::kWordMask);
  return link::plan_word(profile_, word).frame;
}

void FrameTrials::add_frame(FrameBits bits, std::span<float> slot) {
  if (command48(profile_)) {
    const auto audio = signal::synthesize_symbols(profile_, reliability::to_symbols(bits));
    for (std::size_t i = 0; i < audio.size(); ++i) slot[i] += audio[i];
    return;
  }
  const link::PlannedFrame planned =
      link::plan_word(profile_, reliability::frame_word(static_cast<reliability::Frame>(bits)));
  if (planned.frame != bits) throw std::invalid_argument("frame_trials: not a valid frame");
  auto out = slot.first(sound_samples_);
  for (double f : planned.tones_hz) {
    const std::vector<float>& t = tone(f);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += t[i];
  }
}

const std::vector<float>& FrameTrials::tone(double frequency_hz) {
  auto it = tones_.find(frequency_hz);
  if (it == tones_.end()) {
    std::vector<float> samples(sound_samples_, 0.0f);
    const double one[] = {frequency_hz};
    signal::add_chord(samples, one, profile_.tones.tone_amplitude, profile_.tones.edge_ms, profile_.sample_rate_hz);
    it = tones_.emplace(frequency_hz, std::move(samples)).first;
  }
  return it->second;
}

}  // namespace dtmf::bench
