#include "reply_player.h"

#include <spdlog/spdlog.h>

#include <vector>

#include "signal/bin_synthesizer.h"
#include "signal/synthesizer.h"

namespace dtmf::agent {

std::vector<float> reply_audio(const LinkProfile& profile, bool ack, std::optional<std::uint8_t> sequence) {
  if (profile.frame_format == FrameFormat::Command48) {
    return signal::synthesize_named_reply(profile, signal::NamedReply{ack, ack ? sequence.value_or(0) : std::uint8_t{0}});
  }
  return signal::synthesize_reply(profile, ack ? signal::Reply::Ack : signal::Reply::Nack);
}

ReplyTimeline::ReplyTimeline(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink)
    : profile_(profile), sink_(std::move(sink)) {}

void ReplyTimeline::silence_until(long long sample) {
  static const std::vector<float> zeros(4096, 0.0f);
  while (written_ < sample) {
    const auto n = static_cast<std::size_t>(std::min<long long>(sample - written_, static_cast<long long>(zeros.size())));
    sink_->write(std::span<const float>(zeros.data(), n));
    written_ += static_cast<long long>(n);
  }
}

void ReplyTimeline::play(std::vector<float> audio, double audio_ms) {
  // A chord asked for while the previous one still sounds starts right after it.
  silence_until(profile_.samples_for_ms(audio_ms));
  sink_->write(audio);
  written_ += static_cast<long long>(audio.size());
}

void ReplyTimeline::finish(double audio_ms) {
  silence_until(profile_.samples_for_ms(audio_ms));
  sink_->drain();
}

LiveReplyPlayer::LiveReplyPlayer(std::unique_ptr<physical::AudioSink> sink, std::chrono::milliseconds warmup)
    : sink_(std::move(sink)) {
  if (warmup.count() > 0) {
    sink_->write(std::vector<float>(static_cast<std::size_t>(sink_->sample_rate_hz() * warmup.count() / 1000), 0.0f));
    sink_->drain();
  }
  thread_ = std::thread([this] { run(); });
}

LiveReplyPlayer::~LiveReplyPlayer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void LiveReplyPlayer::play(std::vector<float> audio, double) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(audio));
  }
  wake_.notify_one();
}

void LiveReplyPlayer::finish(double) {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [this] { return queue_.empty(); });
}

void LiveReplyPlayer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;
    const std::vector<float> audio = queue_.front();
    lock.unlock();
    try {
      sink_->write(audio);
      sink_->drain();
    } catch (const std::exception& e) {
      spdlog::error("cannot play an answer: {}", e.what());
    }
    lock.lock();
    queue_.pop_front();
    wake_.notify_all();
  }
}

}  // namespace dtmf::agent
