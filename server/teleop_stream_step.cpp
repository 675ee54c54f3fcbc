// TeleopReactor's step: what the stream does whenever an input came (teleop_stream.h). It
// follows the frame in flight and writes its events, keeps the robot renewed jointly, sends
// the next frame the session names, or ends the stream; with nothing to do it asks the
// session when its rules next change and steps again then.
#include <spdlog/spdlog.h>

#include "command_reactor.h"  // status_of
#include "request_validation.h"
#include "teleop_service.h"
#include "teleop_stream.h"

namespace dtmf::server {

namespace {

// A lease is renewed more than twice a second, and twice within it: a lost renewal costs none.
// A renewal due may wait 100 ms for the queue and a frame on air (215 ms at most) before it
// starts: 715 ms at worst, before the session's own renewal (kJointRenewalLate) takes over.
double renewal_every_ms(double lease_s) { return std::min(400.0, 400.0 * lease_s); }

// A client silent this long holds the slot no more (its lease lapsed long ago).
constexpr double kClientGone_s = 10.0;

// What the step could not foresee: the stream ends, and the robot stops at its lease's end.
grpc::Status failure_status(const std::exception& e) {
  return {grpc::StatusCode::INTERNAL, std::string("the Teleop stream failed: ") + e.what() +
                                          "; the robot stops when its lease ends, and a new stream may drive it"};
}

}  // namespace

void TeleopReactor::step() {
  while (!finished_) {
    bool writing = false;
    bool is_open = false;
    {
      std::lock_guard lock(mutex_);
      writing = writing_;
      is_open = opened_;
    }
    if (writing) return;  // OnWriteDone steps again
    const double now_s = steady_s();
    if (!ending_) ending_ = end_due(now_s);
    if (ending_) return end_step();
    if (!is_open) return;  // the first message opens it
    try {
      if (job_) {
        if (!follow_frame(now_s)) return;  // a write, or its next event, steps again
        continue;                          // it ended: an end due, or the next frame
      }
      follow_renewals(now_s);
      const auto due = session_->frame_due(now_s, renewing_);
      if (!due) return wait_for_change(now_s);
      send_frame(*due);
    } catch (const std::exception& e) {
      ending_ = failure_status(e);
    }
  }
}

std::optional<grpc::Status> TeleopReactor::end_due(double now_s) {
  std::lock_guard lock(mutex_);
  if (cancelled_) return grpc::Status{grpc::StatusCode::CANCELLED, "the client cancelled the Teleop stream"};
  if (closed_unopened_) return grpc::Status::OK;
  if (!opened_) return refused_;  // refused at its first message, or not yet read
  if (auto why = session_->halted()) return grpc::Status{grpc::StatusCode::ABORTED, *why};
  if (job_) return std::nullopt;  // the frame in flight ends first
  if (session_->stream_ended()) return refused_.value_or(grpc::Status::OK);
  if (session_->silent_s(now_s) > kClientGone_s) {
    return grpc::Status{grpc::StatusCode::DEADLINE_EXCEEDED,
                        "the client sent nothing for " + std::to_string(static_cast<int>(kClientGone_s)) +
                            " s: the stream is closed (the robot stopped when its lease ended)"};
  }
  return std::nullopt;
}

bool TeleopReactor::follow_frame(double now_s) {
  if (std::optional<ProgressEvent> event = job_->take_event()) {
    using Kind = ProgressEvent::Kind;
    if (event->kind == Kind::Ack || event->kind == Kind::Nack) answered_ = true;
    if (event->kind == Kind::Ack) {
      confirmed_ = true;
      response_ms_ = event->response_time_ms.value_or(0);
    }
    if (event->kind == Kind::Confirmed || event->kind == Kind::Continued || event->kind == Kind::Failed) {
      const auto executed = std::get<command::Velocity>(job_->link().as_received(job_->command()));
      session_->frame_ended(now_s, answered_, confirmed_ ? std::optional(executed) : std::nullopt, response_ms_);
    }
    v1::Progress progress;
    fill_progress(progress, *job_, *event, transmitter_.robot_name(setup_.robot));
    write_status(&progress);
    return false;
  }
  if (!job_->finished_and_drained()) return false;
  job_->on_event(nullptr);
  const std::shared_ptr<Job> job = std::exchange(job_, nullptr);
  if (job->outcome() == Outcome::Unavailable)
    ending_ = grpc::Status(grpc::StatusCode::UNAVAILABLE, job->outcome_detail());
  return true;
}

void TeleopReactor::follow_renewals(double now_s) {
  const bool renewable = session_->renewable(now_s);
  if (renewable && !renewing_) {
    renewing_ = transmitter_.keep_renewed(setup_.robot, *setup_.profile, renewal_every_ms(setup_.carried_lease_s),
                                          1000 * setup_.carried_lease_s);
  } else if (!renewable && renewing_) {
    transmitter_.stop_renewing(setup_.robot);
    renewing_ = false;
  }
  if (renewing_) {
    if (const auto at = transmitter_.last_renewed(setup_.robot)) session_->renewed(steady_s(*at));
  }
}

void TeleopReactor::send_frame(const command::Velocity& velocity) {
  answered_ = confirmed_ = false;
  response_ms_ = 0;
  Submitted submitted =
      transmitter_.submit(velocity, Policy::Live, setup_.decision_timeout, false, setup_.profile, setup_.robot);
  if (auto* refusal = std::get_if<Refusal>(&submitted)) {
    ending_ = status_of(*refusal);
    return;
  }
  job_ = std::get<std::shared_ptr<Job>>(std::move(submitted));
  std::weak_ptr<TeleopReactor> told = self_;
  // The job's events come under the transmitter's locks: the step runs on gRPC's threads.
  job_->on_event([told] {
    if (auto r = told.lock()) r->steps_->run_soon();
  });
}

void TeleopReactor::wait_for_change(double now_s) {
  std::optional<double> at_s = session_->next_change_s(now_s, renewing_);
  const double gone_s = now_s + kClientGone_s - session_->silent_s(now_s) + 0.001;
  if (!at_s || gone_s < *at_s) at_s = gone_s;
  const auto at = std::chrono::steady_clock::time_point(
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(*at_s)));
  steps_->run_at(at);
}

void TeleopReactor::write_status(const v1::Progress* progress) {
  const TeleopStatus s = session_->status(steady_s());
  response_.Clear();
  if (progress) *response_.mutable_progress() = *progress;
  response_.set_target_linear_mps(s.target_linear_mps);
  response_.set_target_angular_radps(s.target_angular_radps);
  response_.set_confirmed(s.confirmed.has_value());
  if (s.confirmed) {
    response_.set_confirmed_linear_mps(s.confirmed->linear_mps);
    response_.set_confirmed_angular_radps(s.confirmed->angular_radps);
  }
  response_.set_response_time_ms(s.response_time_ms);
  response_.set_link_quality(s.link_quality);
  response_.set_frames_in_window(static_cast<std::uint32_t>(s.frames_in_window));
  response_.set_link_window_s(kLinkWindow_s);
  response_.set_lease_s(setup_.carried_lease_s);
  response_.set_lease_left_s(s.lease_left_s);
  {
    std::lock_guard lock(mutex_);
    writing_ = true;
  }
  StartWrite(&response_);
}

void TeleopReactor::end_step() {
  if (job_) {
    job_->on_event(nullptr);
    job_->cancel();  // a chord on air completes; nothing more is sent for this stream
    job_.reset();
  }
  if (renewing_) {
    transmitter_.stop_renewing(setup_.robot);
    renewing_ = false;
  }
  bool is_open = false;
  {
    std::lock_guard lock(mutex_);
    is_open = opened_;
  }
  const grpc::Status status = *ending_;
  if (is_open && !failure_written_ && !status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
    failure_written_ = true;  // the last status says why
    v1::Progress last;
    last.set_event(v1::FRAME_EVENT_FAILED);
    last.set_detail(status.error_message());
    last.set_profile(setup_.profile->name);
    return write_status(&last);
  }
  finished_ = true;
  if (is_open) {
    // Free the robot before the status goes: a client told the stream ended may open the next
    // at once, before gRPC calls OnDone (CI saw that one refused as "another stream drives").
    slot_.reset();
    spdlog::info("teleop stream closed: {}", status.ok() ? "the client ended it" : status.error_message());
  }
  Finish(status);
}

}  // namespace dtmf::server
