// When the bridge opens, writes to and closes a robot's Teleop stream: a small state machine
// fed with what the input wants (twist_input.h) and what the stream says, that answers with
// the one call to make now. Pure logic: the caller gives the time (ms, any steady clock).
//
//   Closed   --input not zero-------------------------> Open      (open the stream with it)
//   Open     --input changed--------------------------> Open      (write it)
//            --input zero (a zero or its timeout)-----> Stopping  (write the zero: the robot
//                                                                   stops at once on hearing it)
//            --nothing new for kRepeatMs--------------> Open      (write it again: the server
//                                                                   ends a stream silent for 1 s)
//   Stopping --the robot confirmed zero, or a lease---> Closing   (close: nothing more on air)
//            --input not zero-------------------------> Open      (write it)
//   Closing  --the stream ended-----------------------> Closed
//   any      --the stream ended ABORTED---------------> Held      (a Stop overtook it)
//   Held     --input zero-----------------------------> Closed
//   any      --the stream failed otherwise------------> Closed, tried again after kRetryMs
//
// Held is a stop's guard: a Stop (the stop for every robot, or anyone's Stop for this robot)
// ends the stream, and a publisher that keeps sending the old velocity (Nav2 at 20 Hz) must
// not drive the robot again. It drives again only after its input has been zero or silent.
#pragma once

#include <optional>
#include <string>

#include "twist_input.h"

namespace dtmf::ros_bridge {

enum class StreamState { Closed, Open, Stopping, Closing, Held };
std::string to_string(StreamState state);

enum class StreamEnd {
  Finished,  // the server ended it after our close (OK), or it was cancelled
  Stopped,   // ABORTED: a Stop overtook it
  Failed,    // anything else: the server is down, another stream holds the robot, ...
};

struct PlanCall {
  enum class Kind { Open, Write, Close } kind;
  Twist target;  // Open, Write
  bool operator==(const PlanCall&) const = default;
};

class TeleopPlan {
 public:
  static constexpr double kRepeatMs = 500;  // the server ends a stream silent for 1000 ms
  static constexpr double kRetryMs = 1000;  // after a failed stream, before opening another

  // `lease_ms`: the lease each frame carries; after it the robot has stopped by itself.
  explicit TeleopPlan(double lease_ms) : lease_ms_(lease_ms) {}

  // The call to make now, if any. Call it after each change of input or stream, and at
  // next_deadline_ms().
  std::optional<PlanCall> step(Twist wanted, double now_ms);
  // The robot confirmed it executes `confirmed` (a TeleopResponse with confirmed set).
  void on_confirmed(Twist confirmed);
  void on_stream_end(StreamEnd end, double now_ms);

  // When step() has something to do without any new input or event.
  std::optional<double> next_deadline_ms() const;
  StreamState state() const { return state_; }

 private:
  PlanCall write(Twist target, double now_ms);

  double lease_ms_;
  StreamState state_ = StreamState::Closed;
  Twist sent_;
  double sent_ms_ = 0;
  double stopping_since_ms_ = 0;
  bool zero_confirmed_ = false;
  std::optional<double> retry_at_ms_;  // after a failed stream: not before
};

}  // namespace dtmf::ros_bridge
