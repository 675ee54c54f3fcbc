// Reliability layer: the sender's retry controller (seed section 7, Fig. 8).
//
// One controller follows one frame. It asks for the first transmission; after a NACK or an
// ACK timeout it asks for `auto_retransmissions` more on its own; after that it asks its
// caller to continue (as if acknowledged), retransmit, or give up, as often as needed,
// until an ACK arrives or the caller stops. An ACK that arrives while a retransmission or a
// decision is pending still confirms the frame (the retransmission is withdrawn).
//
// Pure logic: events come in with the caller's clock reading (`now_ms`, any monotonic
// millisecond scale); the controller never reads a clock or sleeps.
#pragma once

#include <optional>
#include <string>

namespace dtmf::reliability {

struct RetryPolicy {
  int auto_retransmissions = 1;
  double ack_timeout_ms = 0;  // from the start of each chord
};

enum class Answer { Ack, Nack };
enum class Decision { Continue, Retransmit, GiveUp };

enum class RetryState {
  Idle,              // start() not called yet
  TransmitPending,   // the transmitter should send `attempt` (it waits for the channel)
  AwaitingAnswer,    // chord on air or just played; deadline running
  AwaitingDecision,  // automatic retries used up: the caller must decide
  Confirmed,         // an ACK was heard
  Continued,         // the caller chose to go on without confirmation
  Failed,            // the caller gave up
};

std::string retry_state_name(RetryState state);

// Why the latest attempt went unconfirmed.
enum class Miss { None, Nack, Timeout };

class RetryController {
 public:
  explicit RetryController(RetryPolicy policy);

  // Each returns the state after the event. Events that do not fit the state are ignored.
  RetryState start();
  RetryState on_transmit_started(double now_ms);
  RetryState on_answer(Answer answer, double now_ms);
  RetryState on_tick(double now_ms);
  RetryState on_decision(Decision decision);

  RetryState state() const { return state_; }
  bool finished() const;
  int attempt() const { return attempt_; }  // 1 for the first transmission
  Miss last_miss() const { return last_miss_; }
  // When the deadline of the current attempt falls, while AwaitingAnswer.
  std::optional<double> deadline_ms() const;
  // From the start of the answered chord to its ACK / NACK.
  std::optional<double> response_time_ms() const { return response_time_ms_; }

 private:
  RetryState miss(Miss why);

  RetryPolicy policy_;
  RetryState state_ = RetryState::Idle;
  int attempt_ = 0;
  Miss last_miss_ = Miss::None;
  double chord_started_ms_ = 0;
  std::optional<double> response_time_ms_;
};

}  // namespace dtmf::reliability
