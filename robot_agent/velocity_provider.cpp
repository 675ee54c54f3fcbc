#include "velocity_provider.h"
#include "command/overloaded.h"

#include <cstdio>

namespace dtmf::agent {

std::string motion_state_name(MotionState state) {
  switch (state) {
    case MotionState::Idle:
      return "idle";
    case MotionState::Duration:
      return "duration";
    case MotionState::Continuous:
      return "continuous";
  }
  return "unknown";
}

VelocityProvider::VelocityProvider(RobotModel model, double continuous_limit_s)
    : model_(std::move(model)), continuous_limit_s_(continuous_limit_s) {}

Velocity VelocityProvider::drive(double speed_percent) const {
  return {model_.max_linear_mps * speed_percent / 100.0, 0.0};
}

Velocity VelocityProvider::turn(double rotation_percent) const {
  return {0.0, model_.max_angular_rps * rotation_percent / 100.0};
}

void VelocityProvider::apply(const command::Command& command, double now_s) {
  const auto move = [&](Velocity v, MotionState state, double for_s) {
    velocity_ = v;
    state_ = state;
    end_s_ = now_s + for_s;
  };
  std::visit(command::Overloaded{[](const command::Reset&) {}, [&](const command::Stop&) { stop(); },
                                 [&](const command::DriveForDuration& c) {
                                   move(drive(c.speed_percent), MotionState::Duration, c.duration_s);
                                 },
                                 [&](const command::TurnForDuration& c) {
                                   move(turn(c.rotation_percent), MotionState::Duration, c.duration_s);
                                 },
                                 [&](const command::DriveForward& c) {
                                   move(drive(c.speed_percent), MotionState::Continuous, continuous_limit_s_);
                                 },
                                 [&](const command::Turn& c) {
                                   move(turn(c.rotation_percent), MotionState::Continuous, continuous_limit_s_);
                                 }},
             command);
}

void VelocityProvider::stop() {
  state_ = MotionState::Idle;
  velocity_ = {};
}

Velocity VelocityProvider::update(double now_s) {
  if (state_ == MotionState::Duration && now_s >= end_s_) {
    stop();
    stop_reason_ = "duration ended";
  } else if (state_ == MotionState::Continuous && continuous_limit_s_ > 0 && now_s >= end_s_) {
    stop();
    char reason[96];
    std::snprintf(reason, sizeof reason, "continuous motion reached the %.0f s safety limit", continuous_limit_s_);
    stop_reason_ = reason;
  }
  return velocity_;
}

std::optional<std::string> VelocityProvider::take_stop_reason() {
  auto reason = std::move(stop_reason_);
  stop_reason_.reset();
  return reason;
}

}  // namespace dtmf::agent
