#include "frames/frame_trials.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::bench {

void FrameReceiver::feed(std::span<const float> samples, std::vector<Accepted>& accepted) {
  // A repeat (a numbered frame heard again) is accepted and answered too; only its execution
  // is skipped.
  for (const link::Reception& r : receiver_->feed(samples)) {
    if (r.acknowledged())
      accepted.push_back({r.start_ms, r.bits});
    else if (r.intact)
      ++refused_;
    else
      ++check_failed_;
  }
}

ReplyReceiver::ReplyReceiver(link::Link& sender) : sender_(sender), listener_(sender.answer_listener()) {}

void ReplyReceiver::feed(std::span<const float> samples) {
  audio_ms_ += 1000.0 * static_cast<double>(samples.size()) / sender_.profile().sample_rate_hz;
  for (const link::Answer& a : listener_->feed(samples)) {
    (a.ack ? acks_ : nacks_)++;
    while (a.heard_ms >= waiting_until_ms_) {
      waiting_for_ = sender_.random_frame(next_seed_++);
      wait_.emplace(sender_, waiting_for_);
      waiting_until_ms_ += sender_.profile().timing.ack_timeout_ms;
    }
    if (a.ack && wait_ && wait_->answered_by(a)) ++confirmations_;
  }
}

std::vector<std::vector<float>> Responder::feed(std::span<const float> samples) {
  std::vector<std::vector<float>> answers;
  for (const link::Reception& r : receiver_->feed(samples)) answers.push_back(link_.answer_audio(r));
  return answers;
}

FrameTrials::FrameTrials(const LinkProfile& profile, std::shared_ptr<const security::LinkKey> key) {
  link::LinkOptions sender, robot;
  sender.key = robot.key = key;
  if (key) {
    // Both start in step, as after a synchronisation: the sender's counters from 1, the
    // robot having accepted none.
    sender.counters = std::make_shared<security::MemoryCounterStore>(1, 0);
    robot.counters = std::make_shared<security::MemoryCounterStore>(1, 0);
  }
  sender.first_sequence = 0;
  link_ = link::make_link(profile, sender);
  robot_ = link::make_link(profile, robot);
  // A Stop is the shortest command in every format: its frames show a frame's payload.
  const command::Command stop = command::Stop{};
  data_bits_ = link_->payload_bits(stop) / static_cast<int>(link_->frame_count(stop));
  // The sample comes from a link of its own, so that the sender's numbering starts clean.
  link::LinkOptions sampler;
  sampler.key = key;
  const link::TransmitFrame sample = link::make_link(profile, sampler)->random_frame(0);
  check_bits_ = sample.check_bit_count;
  sound_samples_ = sample.audio.size();
  slot_samples_ = static_cast<std::size_t>(profile.samples_for_ms(link_->frame_start_ms(1)));
  if (slot_samples_ < sound_samples_) throw std::logic_error("frame_trials: a frame is longer than its slot");
}

link::TransmitFrame FrameTrials::random_frame(std::mt19937_64& rng) {
  link::TransmitFrame frame = link_->random_frame(rng());
  while (frame.bits == last_bits_) frame = link_->random_frame(rng());
  last_bits_ = frame.bits;
  return frame;
}

link::TransmitFrame FrameTrials::stop_frame() {
  std::vector<link::TransmitFrame> frames = link_->plan(command::Stop{});
  return std::move(frames.back());
}

void FrameTrials::add_frame(const link::TransmitFrame& frame, std::span<float> slot) {
  const std::size_t n = std::min(frame.audio.size(), slot.size());
  for (std::size_t i = 0; i < n; ++i) slot[i] += frame.audio[i];
}

}  // namespace dtmf::bench
