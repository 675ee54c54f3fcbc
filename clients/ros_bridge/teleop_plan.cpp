#include "teleop_plan.h"

namespace dtmf::ros_bridge {

std::string to_string(StreamState state) {
  switch (state) {
    case StreamState::Closed:
      return "closed";
    case StreamState::Open:
      return "open";
    case StreamState::Stopping:
      return "stopping";
    case StreamState::Closing:
      return "closing";
    case StreamState::Held:
      return "held after a stop";
  }
  return "?";
}

PlanCall TeleopPlan::write(Twist target, double now_ms) {
  sent_ = target;
  sent_ms_ = now_ms;
  if (target.is_zero()) {
    if (state_ != StreamState::Stopping) {  // a renewed zero keeps its start and its confirmation
      stopping_since_ms_ = now_ms;
      zero_confirmed_ = false;
    }
    state_ = StreamState::Stopping;
  } else {
    state_ = StreamState::Open;
  }
  return {PlanCall::Kind::Write, target};
}

std::optional<PlanCall> TeleopPlan::step(Twist wanted, double now_ms) {
  switch (state_) {
    case StreamState::Closed:
      if (retry_at_ms_ && now_ms < *retry_at_ms_) return std::nullopt;
      retry_at_ms_.reset();
      if (wanted.is_zero()) return std::nullopt;
      state_ = StreamState::Open;
      sent_ = wanted;
      sent_ms_ = now_ms;
      return PlanCall{PlanCall::Kind::Open, wanted};
    case StreamState::Open:
      if (wanted != sent_ || now_ms - sent_ms_ >= kRepeatMs) return write(wanted, now_ms);
      return std::nullopt;
    case StreamState::Stopping:
      if (!wanted.is_zero()) return write(wanted, now_ms);
      if (zero_confirmed_ || now_ms - stopping_since_ms_ >= lease_ms_) {
        state_ = StreamState::Closing;
        return PlanCall{PlanCall::Kind::Close, {}};
      }
      // Renewing the zero keeps the stream alive until the robot confirms it.
      if (now_ms - sent_ms_ >= kRepeatMs) return write(wanted, now_ms);
      return std::nullopt;
    case StreamState::Closing:
      return std::nullopt;
    case StreamState::Held:
      if (wanted.is_zero()) state_ = StreamState::Closed;
      return std::nullopt;
  }
  return std::nullopt;
}

void TeleopPlan::on_confirmed(Twist confirmed) {
  if (state_ == StreamState::Stopping && confirmed.is_zero()) zero_confirmed_ = true;
}

void TeleopPlan::on_stream_end(StreamEnd end, double now_ms) {
  switch (end) {
    case StreamEnd::Stopped:
      state_ = StreamState::Held;
      break;
    case StreamEnd::Failed:
      state_ = StreamState::Closed;
      retry_at_ms_ = now_ms + kRetryMs;
      break;
    case StreamEnd::Finished:
      state_ = StreamState::Closed;
      break;
  }
}

std::optional<double> TeleopPlan::next_deadline_ms() const {
  switch (state_) {
    case StreamState::Open:
      return sent_ms_ + kRepeatMs;
    case StreamState::Stopping: {
      const double close_at = stopping_since_ms_ + lease_ms_;
      const double repeat_at = sent_ms_ + kRepeatMs;
      return close_at < repeat_at ? close_at : repeat_at;
    }
    case StreamState::Closed:
      return retry_at_ms_;
    case StreamState::Closing:
    case StreamState::Held:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace dtmf::ros_bridge
