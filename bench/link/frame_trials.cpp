#include "link/frame_trials.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::bench {

void FrameReceiver::feed(std::span<const float> samples, std::vector<Accepted>& accepted) {
  // A repeat (a numbered frame heard again) is accepted and answered too; only its execution
  // is skipped.
  for (const link::Reception& r : receiver_->feed(samples)) {
    if (r.intact)
      accepted.push_back({r.start_ms, r.bits});
    else
      ++check_failed_;
  }
}

void ReplyReceiver::feed(std::span<const float> samples) {
  for (const link::Answer& a : listener_->feed(samples)) (a.ack ? acks_ : nacks_)++;
}

std::vector<std::vector<float>> Responder::feed(std::span<const float> samples) {
  std::vector<std::vector<float>> answers;
  for (const link::Reception& r : receiver_->feed(samples)) answers.push_back(link_.answer_audio(r));
  return answers;
}

FrameTrials::FrameTrials(const link::Link& link) : link_(link) {
  // A Stop is the shortest command in every format: its frames show a frame's payload.
  const command::Command stop = command::Stop{};
  data_bits_ = link_.payload_bits(stop) / static_cast<int>(link_.frame_count(stop));
  const link::TransmitFrame sample = link_.random_frame(0);
  check_bits_ = sample.check_bit_count;
  sound_samples_ = sample.audio.size();
  slot_samples_ = static_cast<std::size_t>(link_.profile().samples_for_ms(link_.frame_start_ms(1)));
  if (slot_samples_ < sound_samples_) throw std::logic_error("frame_trials: a frame is longer than its slot");
}

link::TransmitFrame FrameTrials::random_frame(std::mt19937_64& rng) {
  link::TransmitFrame frame = link_.random_frame(rng());
  while (frame.bits == last_bits_) frame = link_.random_frame(rng());
  last_bits_ = frame.bits;
  return frame;
}

void FrameTrials::add_frame(const link::TransmitFrame& frame, std::span<float> slot) {
  const std::size_t n = std::min(frame.audio.size(), slot.size());
  for (std::size_t i = 0; i < n; ++i) slot[i] += frame.audio[i];
}

}  // namespace dtmf::bench
