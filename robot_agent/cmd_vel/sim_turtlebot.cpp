#include "cmd_vel/sim_turtlebot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace dtmf::agent {

SimTurtlebot::SimTurtlebot(command::RobotModel model, Report report)
    : model_(std::move(model)), report_(std::move(report)) {}

void SimTurtlebot::say(double audio_ms, const char* what) {
  char line[160];
  std::snprintf(line, sizeof line, "sim: %s at t=%.2f s: x=%.3f m y=%.3f m heading=%.1f deg, %.3f m driven", what,
                audio_ms / 1000.0, pose_.x_m, pose_.y_m, pose_.theta_rad * 180.0 / std::numbers::pi, distance_m_);
  report_(line);
  last_report_ms_ = audio_ms;
}

void SimTurtlebot::publish(const Velocity& requested, double audio_ms, std::chrono::system_clock::time_point) {
  if (last_ms_ >= 0) {
    const double dt = (audio_ms - last_ms_) / 1000.0;
    const double v = velocity_.linear_mps, w = velocity_.angular_radps;
    if (std::abs(w) < 1e-9) {
      pose_.x_m += v * dt * std::cos(pose_.theta_rad);
      pose_.y_m += v * dt * std::sin(pose_.theta_rad);
    } else {  // along the arc of radius v / w
      const double theta = pose_.theta_rad + w * dt;
      pose_.x_m += v / w * (std::sin(theta) - std::sin(pose_.theta_rad));
      pose_.y_m -= v / w * (std::cos(theta) - std::cos(pose_.theta_rad));
      pose_.theta_rad = std::remainder(theta, 2 * std::numbers::pi);
    }
    distance_m_ += std::abs(v) * dt;
  }
  const Velocity held{std::clamp(requested.linear_mps, -model_.max_linear_mps, model_.max_linear_mps),
                      std::clamp(requested.angular_radps, -model_.max_angular_radps, model_.max_angular_radps)};
  const bool was_moving = velocity_ != Velocity{};
  const bool moving = held != Velocity{};
  velocity_ = held;
  last_ms_ = audio_ms;
  if (was_moving && !moving)
    say(audio_ms, "stopped");
  else if (moving && (!was_moving || audio_ms - last_report_ms_ >= 1000))
    say(audio_ms, "moving");
}

}  // namespace dtmf::agent
