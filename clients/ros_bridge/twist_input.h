// One robot's velocity input, as twist_mux keeps one: the newest message wins, and it holds
// for a timeout after it arrived (twist_mux's 0.5 s by default), then the input is zero.
//
// A message is checked before it is taken: a NaN or infinite component drops the whole
// message (the input keeps the last good one), and a value beyond the robot's limits is
// clamped to them. take() says which, and whether it is the first of its kind, so that the
// bridge says each once instead of once per message at 1 kHz. Pure logic: the caller gives
// the time (milliseconds on any steady clock).
#pragma once

#include <optional>

namespace dtmf::ros_bridge {

struct Twist {
  double linear_mps = 0;     // linear.x
  double angular_radps = 0;  // angular.z
  bool operator==(const Twist&) const = default;
  bool is_zero() const { return linear_mps == 0 && angular_radps == 0; }
};

struct TwistLimits {
  double linear_mps = 0;  // |linear.x| at most
  double angular_radps = 0;
};

enum class TwistVerdict { Taken, Clamped, NotFinite };

struct TakeResult {
  TwistVerdict verdict = TwistVerdict::Taken;
  bool first_of_its_kind = false;  // the first Clamped, or the first NotFinite, of this input
};

class TwistInput {
 public:
  TwistInput(TwistLimits limits, double timeout_ms) : limits_(limits), timeout_ms_(timeout_ms) {}

  TakeResult take(Twist message, double now_ms);
  // The velocity asked for now: the newest message's until its timeout, then zero.
  Twist wanted(double now_ms) const;
  // When the newest message times out, if it is not zero and has not yet; else nothing.
  std::optional<double> expires_ms(double now_ms) const;
  // Messages taken since the start (dropped ones not counted).
  long long taken() const { return taken_; }

 private:
  TwistLimits limits_;
  double timeout_ms_;
  Twist newest_;
  std::optional<double> newest_ms_;
  bool clamped_before_ = false;
  bool dropped_before_ = false;
  long long taken_ = 0;
};

}  // namespace dtmf::ros_bridge
