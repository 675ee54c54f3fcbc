// SenderCore::next: what the loudspeaker does now. One job is on the air at a time, in the
// order of the air: a renewal that is due, else the queue's front. Each phase of the job on
// air (sender_core_frames.cpp) either gives the driver a step or moves the job on; next()
// goes on until one gives a step.
#include <spdlog/spdlog.h>

#include "sender_core.h"

namespace dtmf::server {

using Kind = ProgressEvent::Kind;

namespace {
// Why a job ended cancelled: its caller, or a Stop that overtook it.
std::string cancelled_detail(Job& job) {
  return job.overtaken() ? "overtaken by a Stop, which went on the air at once: its answer was not awaited (the "
                           "robot may have executed it); send it again after the stop"
                         : "cancelled by the caller";
}
}  // namespace

SenderCore::Step SenderCore::next(double now_ms) {
  while (true) {
    if (!sending_) {
      if (stopping_) {
        end_queued(Outcome::Unavailable, "the server is shutting down", now_ms);
        return Idle{};
      }
      if (!take_next(now_ms)) return idle_step();
      // A renewal's Queued is handed over (and recorded) before it can play: see withdraw().
      if (sending_->job->renewal()) return WaitUntil{now_ms};
    }
    if (const MaybeStep step = phase_step(*sending_, now_ms)) return *step;
  }
}

SenderCore::MaybeStep SenderCore::phase_step(Sending& s, double now_ms) {
  switch (s.phase) {
    case Sending::Phase::NextFrame:
      return next_frame(s, now_ms);
    case Sending::Phase::Air:
      return await_air(s, now_ms);
    case Sending::Phase::Playing:
      return playing(s, now_ms);
    case Sending::Phase::Answer:
      return await_answer(s, now_ms);
    case Sending::Phase::Decision:
      return await_decision(s, now_ms);
  }
  return std::nullopt;
}

bool SenderCore::take_next(double now_ms) {
  const std::vector<RobotIndex> renew = renewals_due(now_ms);
  if (!renew.empty() && start_renewal(renew, now_ms)) return true;
  if (queue_.empty()) return false;
  sending_ = Sending{queue_.front()};
  queue_.pop_front();
  Job& job = *sending_->job;
  if (std::holds_alternative<command::Stop>(job.command())) stop_waiting_ = false;
  try {
    job.plan();  // numbered now, in the order of the air
  } catch (const std::exception& e) {
    // The parameters were checked when it was queued; what fails here is the counter's
    // store (a disk that went away): the command cannot go out authenticated.
    spdlog::error("{}: cannot plan its frames: {}", job.description(), e.what());
    end(*sending_, Outcome::Unavailable, std::string("cannot number its frames: ") + e.what(), now_ms);
  }
  return true;
}

SenderCore::Step SenderCore::idle_step() const {
  if (const auto due = renewals_.next_due_ms()) return WaitUntil{*due};
  return Idle{};
}

ProgressEvent SenderCore::attempt_event(const Sending& s, Kind kind) const {
  ProgressEvent e{kind};
  e.frame = s.job->frames().at(static_cast<std::size_t>(s.index));
  e.frame_count = s.job->frame_count();
  e.frame_index = s.index;
  e.attempt = s.retry ? s.retry->attempt() : 0;
  return e;
}

void SenderCore::end(Sending& s, Outcome outcome, const std::string& detail, double now_ms) {
  const std::shared_ptr<Job> job = s.job;
  ProgressEvent last{outcome == Outcome::Confirmed   ? Kind::Confirmed
                     : outcome == Outcome::Continued ? Kind::Continued
                     : outcome == Outcome::Sent      ? Kind::Sent
                                                     : Kind::Failed};
  last.outcome = outcome;
  last.frame_count = job->frame_count();
  if (!job->frames().empty()) {
    last.frame_index = job->frame_count() - 1;
    last.frame = job->frames().back();
  }
  last.detail = detail;
  emit(job, last, now_ms);
  spdlog::info("{}: {}{}", job->description(), outcome_name(outcome), detail.empty() ? "" : " (" + detail + ")");
  // A renewal ends: the command it went between goes on.
  sending_ = std::exchange(between_, std::nullopt);
}

void SenderCore::end_cancelled(Sending& s, double now_ms) {
  end(s, stopping_ ? Outcome::Unavailable : Outcome::Cancelled,
      stopping_ ? "the server is shutting down" : cancelled_detail(*s.job), now_ms);
}

void SenderCore::shutdown() { stopping_ = true; }

void SenderCore::audio_failed(std::string why, double now_ms) {
  if (unavailable_.empty()) unavailable_ = std::move(why);
  // Our exchange ends with it: nothing of ours is on the air any more.
  if (sending_ && (sending_->phase == Sending::Phase::Playing || sending_->phase == Sending::Phase::Answer))
    exchange_ended(now_ms);
  while (sending_) end(*sending_, Outcome::Unavailable, unavailable_, now_ms);
  end_queued(Outcome::Unavailable, unavailable_, now_ms);
}

void SenderCore::end_queued(Outcome outcome, const std::string& detail, double now_ms) {
  for (auto& waiting : queue_) {
    sending_ = Sending{waiting};
    end(*sending_, outcome, detail, now_ms);
  }
  queue_.clear();
}

}  // namespace dtmf::server
