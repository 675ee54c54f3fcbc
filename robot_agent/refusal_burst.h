// A burst of frames refused for authentication: forgeries, or a sender under another key.
//
// Each refusal is logged and stored on its own; a burst of them is what an operator must
// see at once. RefusalBurst counts refusals over the last minute of the agent's clock (audio
// milliseconds) and says so once when the count reaches kBurstPerMinute, then stays quiet
// until the count has fallen below it again. Pure logic: the caller gives the times.
#pragma once

#include <deque>
#include <optional>

namespace dtmf::agent {

inline constexpr double kBurstWindowMs = 60'000;
inline constexpr int kBurstPerMinute = 10;  // refusals in a minute that make a burst (docs/security.md)

class RefusalBurst {
 public:
  // A refusal at `at_ms` (never earlier than the last). The refusals in the minute up to it
  // when a burst begins with this one, else nothing.
  std::optional<int> refused(double at_ms);
  // Refusals in the minute up to the last one.
  int in_last_minute() const { return static_cast<int>(times_ms_.size()); }

 private:
  std::deque<double> times_ms_;
  bool in_burst_ = false;
};

}  // namespace dtmf::agent
