#include "twist_input.h"

#include <algorithm>
#include <cmath>

namespace dtmf::ros_bridge {

TakeResult TwistInput::take(Twist message, double now_ms) {
  if (!std::isfinite(message.linear_mps) || !std::isfinite(message.angular_radps)) {
    const bool first = !dropped_before_;
    dropped_before_ = true;
    return {TwistVerdict::NotFinite, first};
  }
  const Twist clamped{std::clamp(message.linear_mps, -limits_.linear_mps, limits_.linear_mps),
                      std::clamp(message.angular_radps, -limits_.angular_radps, limits_.angular_radps)};
  newest_ = clamped;
  newest_ms_ = now_ms;
  ++taken_;
  if (clamped == message) return {TwistVerdict::Taken, false};
  const bool first = !clamped_before_;
  clamped_before_ = true;
  return {TwistVerdict::Clamped, first};
}

Twist TwistInput::wanted(double now_ms) const {
  if (!newest_ms_ || now_ms - *newest_ms_ >= timeout_ms_) return {};
  return newest_;
}

std::optional<double> TwistInput::expires_ms(double now_ms) const {
  if (!newest_ms_ || newest_.is_zero()) return std::nullopt;
  const double at = *newest_ms_ + timeout_ms_;
  if (at <= now_ms) return std::nullopt;
  return at;
}

}  // namespace dtmf::ros_bridge
