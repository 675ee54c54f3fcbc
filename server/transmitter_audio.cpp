// Transmitter: its two threads. The loudspeaker's asks the core what to do and does it; the
// microphone's reads blocks, hears them with the ears, and hands the core what they heard.
// Neither polls: the loudspeaker's thread sleeps until the core's next time or an input.
#include <spdlog/spdlog.h>

#include "physical/realtime_priority.h"
#include "transmitter.h"

namespace dtmf::server {

void Transmitter::shutdown() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && !worker_.joinable()) return;
    stopping_ = true;
    core_.shutdown();
    ++inputs_;
  }
  woken_.notify_all();
  if (worker_.joinable()) worker_.join();
  if (listener_.joinable()) listener_.join();
  {
    std::lock_guard lock(waking_->mutex);
    waking_->transmitter = nullptr;  // jobs kept by callers wake nothing any more
  }
  air_events_.close();  // after the threads: nothing more is published
}

void Transmitter::play(const SenderCore::Play& play) {
  try {
    speaker_->write(play.frame->audio);
  } catch (const std::exception& e) {
    const std::string why = std::string("the loudspeaker failed: ") + e.what();
    spdlog::error("{}", why);
    std::unique_lock lock(mutex_);
    core_.audio_failed(why, now_ms());
  }
}

void Transmitter::run() {
  if (realtime_audio_) {
    std::string how;
    physical::raise_audio_thread_priority(&how);
    spdlog::info("loudspeaker thread: {}", how);
  }
  std::unique_lock lock(mutex_);
  while (true) {
    const std::uint64_t seen = inputs_;
    const SenderCore::Step step = core_.next(now_ms());
    deliver(lock);
    if (core_.finished()) return;
    if (const auto* p = std::get_if<SenderCore::Play>(&step)) {
      lock.unlock();
      play(*p);  // a file sink takes the audio at once: the core keeps the pace of a real loudspeaker
      lock.lock();
      continue;
    }
    const auto moved = [&] { return inputs_ != seen; };
    if (const auto* w = std::get_if<SenderCore::WaitUntil>(&step))
      woken_.wait_until(lock, steady(w->at_ms), moved);
    else
      woken_.wait(lock, moved);
  }
}

// Decodes at normal priority: a device is drained by a thread of its own
// (physical/capture_thread.h), which only copies.
void Transmitter::listen() {
  ReplyListeners& ears = *ears_;
  const double rate_hz = profile().sample_rate_hz;
  std::vector<float> block(static_cast<std::size_t>(ears.block_samples()));
  double audio_ms = 0;
  while (true) {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
    }
    std::size_t got = 0;
    try {
      got = microphone_->read(block);
    } catch (const std::exception& e) {
      const std::string why = std::string("the microphone failed: ") + e.what();
      spdlog::error("{}", why);
      {
        std::lock_guard lock(mutex_);
        core_.audio_failed(why, now_ms());
        ++inputs_;
      }
      woken_.notify_all();
      return;
    }
    if (got == 0) return;  // the input ended (a file, or a stopped simulated air)
    audio_ms += 1000.0 * static_cast<double>(got) / rate_hz;
    const double now = now_ms();
    mic_offset_ms_ = now - audio_ms;
    const std::span<const float> heard_block(block.data(), got);
    const double level_dbfs = reliability::block_level_dbfs(heard_block);
    bool busy = false;
    double floor_dbfs = 0;
    {
      // A level wakes nobody: a frame waiting for the air is asked again at the time the core
      // named (reliability::AirAccess::start_at: "call again at that time"). Asked at every
      // block instead, two senders started into each other's exchanges 3 runs in 8
      // (ListenBeforeTalk.TwoSendersInOneRoomNeverStartIntoTheOthersExchange), never so.
      std::lock_guard lock(mutex_);
      core_.hear_level(level_dbfs, now);
      busy = core_.busy_now();
      floor_dbfs = core_.floor_dbfs();
    }
    publish_levels(heard_block, audio_ms, busy, level_dbfs, floor_dbfs);
    const std::vector<HeardAnswer> answers = ears.feed(heard_block);  // outside the lock: the FFTs
    // Watchers hear an answer before what the core makes of it (the frame answered, the
    // command ended), as the air had it: published after, a watcher could read a command's
    // end before the answer that ended it.
    for (const HeardAnswer& heard : answers) publish_heard(heard, heard.answer.heard_ms, level_dbfs);
    if (!answers.empty()) {
      std::lock_guard lock(mutex_);
      // The block just read ends now; each answer was heard a little earlier.
      for (const HeardAnswer& heard : answers) core_.hear_answer(heard, now - (audio_ms - heard.answer.heard_ms));
      ++inputs_;
    }
    if (!answers.empty()) woken_.notify_all();
  }
}

}  // namespace dtmf::server
