#include "refusal_burst.h"

namespace dtmf::agent {

std::optional<int> RefusalBurst::refused(double at_ms) {
  while (!times_ms_.empty() && times_ms_.front() <= at_ms - kBurstWindowMs) times_ms_.pop_front();
  // Below the threshold before this one: any burst has ended.
  if (static_cast<int>(times_ms_.size()) < kBurstPerMinute - 1) in_burst_ = false;
  times_ms_.push_back(at_ms);
  if (in_burst_ || static_cast<int>(times_ms_.size()) < kBurstPerMinute) return std::nullopt;
  in_burst_ = true;
  return static_cast<int>(times_ms_.size());
}

}  // namespace dtmf::agent
