// SenderCore: listen before talk. Every microphone block's level goes to the carrier sense;
// before each frame the core waits for the air (reliability/air_access.h), and marks its
// exchange so that its own sound is not taken for another's.
#include <spdlog/spdlog.h>

#include <algorithm>

#include "sender_core.h"

namespace dtmf::server {

reliability::AirUse SenderCore::air_use(const Job& job) const {
  using reliability::AirUse;
  if (const auto* stop = std::get_if<command::Stop>(&job.command()))
    return stop->every_robot ? AirUse::EveryRobotStop : AirUse::Stop;
  return job.policy() == Policy::Live || job.renewal() ? AirUse::Renewal : AirUse::Command;
}

void SenderCore::hear_level(double level_dbfs, double at_ms) {
  const bool ours = carrier_.own_on();
  carrier_.hear(level_dbfs, at_ms);
  if (carrier_.busy_now())
    spdlog::debug("the air at {:.0f} ms: {:.1f} dBFS over a floor of {:.1f}: another's sound{}", at_ms, level_dbfs,
                  carrier_.floor_dbfs(), ours ? " (while our exchange goes on: counted if not our answer)" : "");
}

SenderCore::MaybeStep SenderCore::await_air(Sending& s, double now_ms) {
  Job& job = *s.job;
  if (s.ending(stopping_)) {
    end_cancelled(s, now_ms);
    return std::nullopt;
  }
  // One chord on air at a time, with the profile's silence between chords, and none into
  // another sender's exchange.
  reliability::AirWait& wait = job.air_wait();
  const bool was_waiting = wait.since_ms.has_value();
  double at = std::max(now_ms, channel_free_ms_);
  if (air_) at = std::max(at, air_->start_at(carrier_, now_ms, air_use(job), wait));
  if (at <= now_ms) {
    if (air_) {
      // Why it may start now: what tells a start into another's exchange from one it could not hear.
      const auto ago = [now_ms](std::optional<double> t) { return t ? now_ms - *t : -1.0; };
      spdlog::debug(
          "the air for command {}: starts at {:.0f} ms; another's sound {:.0f} ms ago, quiet for {:.0f} ms, "
          "another's answer read {:.0f} ms ago (-1: never, or not now)",
          job.id(), now_ms, ago(carrier_.last_busy_ms()), ago(carrier_.quiet_since_ms()),
          ago(carrier_.answered_exchange_ms()));
      air_->started(carrier_, now_ms, wait);
    }
    carrier_.own_begin(now_ms);
    return play(s, now_ms);
  }
  if (!was_waiting && wait.since_ms) tell_waiting(s, wait, now_ms);
  return WaitUntil{at};
}

void SenderCore::tell_waiting(Sending& s, const reliability::AirWait& wait, double now_ms) {
  const Job& job = *s.job;
  ProgressEvent waiting = attempt_event(s, ProgressEvent::Kind::WaitingForAir);
  waiting.air_wait_reason = reliability::air_wait_text(wait.reason);
  // The most it may still wait: a stop's own bound, or what is left of its command's.
  waiting.air_wait_left_ms = air_use(job) == reliability::AirUse::Stop
                                 ? reliability::kMaxStopWaitMs
                                 : std::max(0.0, reliability::kMaxDeferToUnknownMs - wait.total_ms(now_ms));
  waiting.detail = "waiting for the air: " + waiting.air_wait_reason;
  // A command's wait for the operator's log; a Teleop frame's or renewal's, several a second
  // in a shared room, for debugging only.
  const bool live = job.renewal() || job.policy() == Policy::Live;
  spdlog::log(live ? spdlog::level::debug : spdlog::level::info,
              "{} (command {}, frame {}, attempt {}): {} (at most {:.1f} s more)", job.description(), job.id(),
              waiting.frame_index, waiting.attempt, waiting.detail, waiting.air_wait_left_ms / 1000);
  emit(s.job, std::move(waiting), now_ms);
}

void SenderCore::exchange_ended(double now_ms, std::optional<reliability::AirSpan> answer, bool unconfirmed) {
  const std::size_t busy_before = carrier_.busy_blocks();
  carrier_.own_end(now_ms, answer);
  if (carrier_.busy_blocks() > busy_before)
    spdlog::debug(
        "the air: {} blocks heard during our exchange, outside our answer ({:.0f}..{:.0f} ms, now {:.0f}), "
        "were another's",
        carrier_.busy_blocks() - busy_before, answer ? answer->from_ms : -1.0, answer ? answer->to_ms : -1.0, now_ms);
  if (air_ && unconfirmed) air_->unanswered(carrier_, now_ms);
}

}  // namespace dtmf::server
