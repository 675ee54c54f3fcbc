#include "reply_player.h"

#include <spdlog/spdlog.h>

#include <vector>

#include "physical/realtime_priority.h"

namespace dtmf::agent {

ReplyTimeline::ReplyTimeline(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink)
    : profile_(profile), sink_(std::move(sink)) {}

void ReplyTimeline::silence_until(long long sample) {
  static const std::vector<float> zeros(4096, 0.0f);
  while (written_ < sample) {
    const auto n =
        static_cast<std::size_t>(std::min<long long>(sample - written_, static_cast<long long>(zeros.size())));
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

LiveReplyPlayer::LiveReplyPlayer(std::unique_ptr<physical::AudioSink> sink, std::chrono::milliseconds warmup,
                                 bool realtime)
    : sink_(std::move(sink)) {
  if (warmup.count() > 0) {
    sink_->write(std::vector<float>(static_cast<std::size_t>(sink_->sample_rate_hz() * warmup.count() / 1000), 0.0f));
    sink_->drain();
  }
  thread_ = std::thread([this, realtime] {
    if (realtime) physical::raise_audio_thread_priority();
    run();
  });
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
