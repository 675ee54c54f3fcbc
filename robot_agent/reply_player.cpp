#include "reply_player.h"

#include <spdlog/spdlog.h>

#include <vector>

#include "signal/synthesizer.h"

namespace dtmf::agent {

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

void ReplyTimeline::play(signal::Reply reply, double audio_ms) {
  // A chord asked for while the previous one still sounds starts right after it.
  silence_until(profile_.samples_for_ms(audio_ms));
  const std::vector<float> chord = signal::synthesize_reply(profile_, reply);
  sink_->write(chord);
  written_ += static_cast<long long>(chord.size());
}

void ReplyTimeline::finish(double audio_ms) {
  silence_until(profile_.samples_for_ms(audio_ms));
  sink_->drain();
}

LiveReplyPlayer::LiveReplyPlayer(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink)
    : profile_(profile), sink_(std::move(sink)), thread_([this] { run(); }) {}

LiveReplyPlayer::~LiveReplyPlayer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void LiveReplyPlayer::play(signal::Reply reply, double) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(reply);
  }
  wake_.notify_one();
}

void LiveReplyPlayer::finish(double) {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [this] { return queue_.empty(); });
}

void LiveReplyPlayer::run() {
  const std::vector<float> ack = signal::synthesize_reply(profile_, signal::Reply::Ack);
  const std::vector<float> nack = signal::synthesize_reply(profile_, signal::Reply::Nack);
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;
    const signal::Reply reply = queue_.front();
    lock.unlock();
    try {
      sink_->write(reply == signal::Reply::Ack ? ack : nack);
      sink_->drain();
    } catch (const std::exception& e) {
      spdlog::error("cannot answer with {}: {}", reply == signal::Reply::Ack ? "ACK" : "NACK", e.what());
    }
    lock.lock();
    queue_.pop_front();
    wake_.notify_all();
  }
}

}  // namespace dtmf::agent
