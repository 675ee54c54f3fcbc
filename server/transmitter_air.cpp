// Transmitter: listen before talk. The microphone's reader (listen()) feeds every block's
// level to the carrier sense; before each frame the loudspeaker's thread waits for the air
// (reliability/air_access.h), and marks its exchange so that its own sound is not taken
// for another's.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "transmitter.h"

namespace dtmf::server {

namespace {
// How often a frame waiting for the air looks whether its command was cancelled.
constexpr double kCancelCheckMs = 20;
}  // namespace

double Transmitter::answer_silence_ms() const {
  double longest = 0;
  const auto consider = [&longest](const link::Link& l) {
    longest = std::max(longest, l.profile().timing.ack_timeout_ms - l.profile().timing.chord_ms);
  };
  for (const Robot& r : robots_)
    for (const link::Link* l : r.links) consider(*l);
  for (const auto& l : room_links_) consider(*l);
  return longest;
}

namespace {
reliability::AirUse air_use(const Job& job) {
  using reliability::AirUse;
  if (const auto* stop = std::get_if<command::Stop>(&job.command()))
    return stop->every_robot ? AirUse::EveryRobotStop : AirUse::Stop;
  return job.policy() == Policy::Live || job.renewal() ? AirUse::Renewal : AirUse::Command;
}
}  // namespace

void Transmitter::tell_waiting(Job& job, ProgressEvent waiting, const reliability::AirWait& wait, double now_ms) {
  waiting.kind = ProgressEvent::Kind::WaitingForAir;
  waiting.air_wait_reason = reliability::air_wait_text(wait.reason);
  // The most it may still wait: a stop's own bound, or what is left of its command's.
  waiting.air_wait_left_ms = air_use(job) == reliability::AirUse::Stop
                                 ? reliability::kMaxStopWaitMs
                                 : std::max(0.0, reliability::kMaxDeferToUnknownMs - wait.total_ms(now_ms));
  waiting.detail = "waiting for the air: " + waiting.air_wait_reason;
  waiting.time = wall(now_ms);
  // A command's wait for the operator's log; a Teleop frame's or renewal's, several a second
  // in a shared room, for debugging only.
  const bool live = job.renewal() || job.policy() == Policy::Live;
  spdlog::log(live ? spdlog::level::debug : spdlog::level::info,
              "{} (command {}, frame {}, attempt {}): {} (at most {:.1f} s more)", job.description(), job.id(),
              waiting.frame_index, waiting.attempt, waiting.detail, waiting.air_wait_left_ms / 1000);
  emit(job, std::move(waiting));
}

bool Transmitter::wait_for_air(Job& job, ProgressEvent waiting) {
  const reliability::AirUse use = air_use(job);
  reliability::AirWait& wait = job.air_wait();
  std::unique_lock lock(mutex_);
  while (true) {
    const double now = now_ms();
    double at = std::max(now, channel_free_ms_);
    const bool was_waiting = wait.since_ms.has_value();
    if (air_) at = std::max(at, air_->start_at(carrier_, now, use, wait));
    if (at <= now) {
      if (air_) {
        // Why it may start now: what tells a start into another's exchange from one it could not hear.
        const auto ago = [now](std::optional<double> t) { return t ? now - *t : -1.0; };
        spdlog::debug(
            "the air for command {}: starts at {:.0f} ms; another's sound {:.0f} ms ago, quiet for {:.0f} ms, "
            "another's answer read {:.0f} ms ago (-1: never, or not now)",
            job.id(), now, ago(carrier_.last_busy_ms()), ago(carrier_.quiet_since_ms()),
            ago(carrier_.answered_exchange_ms()));
        air_->started(carrier_, now, wait);
      }
      carrier_.own_begin(now);
      return true;
    }
    if (stopping_ || job.cancelled()) return false;
    if (!was_waiting && wait.since_ms) {
      // Told outside the lock: the observer writes a record, the caller's stream reads it.
      const reliability::AirWait told = wait;
      lock.unlock();
      tell_waiting(job, waiting, told, now);
      lock.lock();
      continue;
    }
    changed_.wait_for(lock, std::chrono::duration<double, std::milli>(std::min(at - now, kCancelCheckMs)));
  }
}

void Transmitter::frame_ended() {
  std::lock_guard lock(mutex_);
  carrier_.frame_ended(now_ms());
}

void Transmitter::exchange_ended(std::optional<reliability::AirSpan> answer, bool unconfirmed) {
  std::lock_guard lock(mutex_);
  const double now = now_ms();
  const std::size_t busy_before = carrier_.busy_blocks();
  carrier_.own_end(now, answer);
  if (carrier_.busy_blocks() > busy_before)
    spdlog::debug(
        "the air: {} blocks heard during our exchange, outside our answer ({:.0f}..{:.0f} ms, now {:.0f}), "
        "were another's",
        carrier_.busy_blocks() - busy_before, answer ? answer->from_ms : -1.0, answer ? answer->to_ms : -1.0, now);
  if (air_ && unconfirmed) air_->unanswered(carrier_, now);
}

AirShare Transmitter::air_share() const {
  std::lock_guard lock(mutex_);
  AirShare share;
  share.busy_blocks = carrier_.busy_blocks();
  share.others_answers = carrier_.others_answers();
  share.masked_answers = carrier_.masked_answers();
  if (air_) {
    share.deferred = air_->deferred();
    share.answered_waits = air_->answered_waits();
    share.yields = air_->yields();
    share.listens = air_->listens();
  }
  return share;
}

}  // namespace dtmf::server
