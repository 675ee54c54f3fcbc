#include "reliability/retry_controller.h"

namespace dtmf::reliability {

std::string retry_state_name(RetryState state) {
  switch (state) {
    case RetryState::Idle:
      return "idle";
    case RetryState::TransmitPending:
      return "transmit_pending";
    case RetryState::AwaitingAnswer:
      return "awaiting_answer";
    case RetryState::AwaitingDecision:
      return "awaiting_decision";
    case RetryState::Confirmed:
      return "confirmed";
    case RetryState::Continued:
      return "continued";
    case RetryState::Failed:
      return "failed";
  }
  return "unknown";
}

RetryController::RetryController(RetryPolicy policy) : policy_(policy) {}

bool RetryController::finished() const {
  return state_ == RetryState::Confirmed || state_ == RetryState::Continued || state_ == RetryState::Failed;
}

std::optional<double> RetryController::deadline_ms() const {
  if (state_ != RetryState::AwaitingAnswer) return std::nullopt;
  return chord_started_ms_ + policy_.ack_timeout_ms;
}

RetryState RetryController::start() {
  if (state_ == RetryState::Idle) {
    attempt_ = 1;
    state_ = RetryState::TransmitPending;
  }
  return state_;
}

RetryState RetryController::on_transmit_started(double now_ms) {
  if (state_ == RetryState::TransmitPending) {
    chord_started_ms_ = now_ms;
    state_ = RetryState::AwaitingAnswer;
  }
  return state_;
}

RetryState RetryController::miss(Miss why) {
  last_miss_ = why;
  // attempt_ counts transmissions: the first plus the automatic retransmissions.
  if (attempt_ <= policy_.auto_retransmissions) {
    ++attempt_;
    state_ = RetryState::TransmitPending;
  } else {
    state_ = RetryState::AwaitingDecision;
  }
  return state_;
}

RetryState RetryController::on_answer(Answer answer, double now_ms) {
  if (answer == Answer::Ack) {
    // A late ACK still proves the frame arrived, even once a retry or a question is pending.
    const bool answerable = state_ == RetryState::AwaitingAnswer || state_ == RetryState::TransmitPending ||
                            state_ == RetryState::AwaitingDecision;
    if (answerable && attempt_ > 0) {
      response_time_ms_ = now_ms - chord_started_ms_;
      last_miss_ = Miss::None;
      state_ = RetryState::Confirmed;
    }
    return state_;
  }
  if (state_ != RetryState::AwaitingAnswer) return state_;
  response_time_ms_ = now_ms - chord_started_ms_;
  return miss(Miss::Nack);
}

RetryState RetryController::on_tick(double now_ms) {
  if (state_ == RetryState::AwaitingAnswer && now_ms >= *deadline_ms()) {
    response_time_ms_.reset();
    return miss(Miss::Timeout);
  }
  return state_;
}

RetryState RetryController::on_decision(Decision decision) {
  if (state_ != RetryState::AwaitingDecision) return state_;
  switch (decision) {
    case Decision::Continue:
      state_ = RetryState::Continued;
      break;
    case Decision::Retransmit:
      ++attempt_;
      state_ = RetryState::TransmitPending;
      break;
    case Decision::GiveUp:
      state_ = RetryState::Failed;
      break;
  }
  return state_;
}

}  // namespace dtmf::reliability
