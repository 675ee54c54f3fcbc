// Transmitter: the loudspeaker's thread. run() takes, in the order of the air, the renewals
// due and the queued commands, one at a time, until shutdown() ends it.
#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

#include "physical/realtime_priority.h"
#include "transmitter.h"

namespace dtmf::server {

void Transmitter::shutdown() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && !worker_.joinable()) return;
    stopping_ = true;
    if (on_air_) on_air_->cancel();
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
  if (listener_.joinable()) listener_.join();
  air_events_.close();  // after the threads: nothing more is published
}

void Transmitter::play(const link::TransmitFrame& frame, double start_ms) {
  speaker_->write(frame.audio);
  // A file sink takes the audio at once: keep the pace of a real loudspeaker anyway.
  const double end_ms = start_ms + frame.tone_ms;
  while (now_ms() < end_ms) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(end_ms - now_ms()));
}

void Transmitter::run() {
  if (options_.realtime_audio) {
    std::string how;
    physical::raise_audio_thread_priority(&how);
    spdlog::info("loudspeaker thread: {}", how);
  }
  while (true) {
    std::shared_ptr<Job> job;
    std::vector<RobotIndex> renew;
    {
      std::unique_lock lock(mutex_);
      while (!stopping_ && queue_.empty() && (renew = renewals_due()).empty()) {
        if (const auto next = renewals_.next_due_ms())
          changed_.wait_for(lock, std::chrono::duration<double, std::milli>(std::max(0.0, *next - now_ms())));
        else
          changed_.wait(lock);
      }
      if (stopping_) {
        for (auto& waiting : queue_) end(*waiting, Outcome::Unavailable, "the server is shutting down");
        queue_.clear();
        return;
      }
      if (renew.empty()) renew = renewals_due();
      if (renew.empty()) {
        job = queue_.front();
        queue_.pop_front();
        on_air_ = job;
        if (std::holds_alternative<command::Stop>(job->command())) stop_waiting_ = false;
      }
    }
    if (!renew.empty()) {
      send_renewal(renew);
      continue;
    }
    try {
      job->plan();  // numbered now, in the order of the air
    } catch (const std::exception& e) {
      // The parameters were checked when it was queued; what fails here is the counter's
      // store (a disk that went away): the command cannot go out authenticated.
      spdlog::error("{}: cannot plan its frames: {}", job->description(), e.what());
      end(*job, Outcome::Unavailable, std::string("cannot number its frames: ") + e.what());
      std::lock_guard lock(mutex_);
      on_air_.reset();
      continue;
    }
    send(*job);
    {
      std::lock_guard lock(mutex_);
      on_air_.reset();
    }
  }
}

}  // namespace dtmf::server
