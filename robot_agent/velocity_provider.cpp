#include "velocity_provider.h"
#include "command/overloaded.h"

#include <algorithm>
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
    case MotionState::Leased:
      return "leased";
  }
  return "unknown";
}

VelocityProvider::VelocityProvider(command::RobotModel model, double continuous_limit_s)
    : model_(std::move(model)), continuous_limit_s_(continuous_limit_s) {}

Velocity VelocityProvider::drive(double speed_percent) const {
  return {model_.max_linear_mps * speed_percent / 100.0, 0.0};
}

Velocity VelocityProvider::turn(double rotation_percent) const {
  return {0.0, model_.max_angular_radps * rotation_percent / 100.0};
}

void VelocityProvider::apply(const command::Command& command, double now_s, std::optional<double> spoken_s) {
  const auto move = [&](Velocity v, MotionState state, double for_s) {
    velocity_ = target_ = v;
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
                                 },
                                 [&](const command::Velocity& c) { lease(c, now_s, spoken_s.value_or(now_s)); }},
             command);
}

void VelocityProvider::lease(const command::Velocity& c, double now_s, double spoken_s) {
  // The ramp so far runs at the old target up to now; from now on towards the new one.
  ramp(now_s);
  target_ = {command::linear_mps(model_, c), command::angular_radps(model_, c)};
  state_ = MotionState::Leased;
  end_s_ = spoken_s + c.lease_s;
}

void VelocityProvider::ramp(double now_s) {
  const double dt_s = std::max(0.0, now_s - ramped_at_s_);
  ramped_at_s_ = now_s;
  const auto approach = [dt_s](double from, double to, double rate) {
    const double step = rate * dt_s;
    // Within a rounding error of the target is the target: zero must be exactly zero.
    return std::abs(to - from) <= step + 1e-12 ? to : std::clamp(to, from - step, from + step);
  };
  velocity_.linear_mps = approach(velocity_.linear_mps, target_.linear_mps, model_.linear_accel_mps2);
  velocity_.angular_radps = approach(velocity_.angular_radps, target_.angular_radps, model_.angular_accel_rps2);
}

bool VelocityProvider::changing_by_itself() const {
  return state_ == MotionState::Duration || state_ == MotionState::Leased || !(velocity_ == target_);
}

void VelocityProvider::stop() {
  state_ = MotionState::Idle;
  velocity_ = target_ = {};
}

std::optional<double> VelocityProvider::settles_at_s() const {
  if (velocity_ != target_) {
    return ramped_at_s_ +
           std::max(std::abs(target_.linear_mps - velocity_.linear_mps) / model_.linear_accel_mps2,
                    std::abs(target_.angular_radps - velocity_.angular_radps) / model_.angular_accel_rps2);
  }
  if (state_ == MotionState::Leased) return end_s_;
  return std::nullopt;
}

double VelocityProvider::stopping_time_s(const Velocity& from) const {
  return std::max(std::abs(from.linear_mps) / model_.linear_accel_mps2,
                  std::abs(from.angular_radps) / model_.angular_accel_rps2);
}

Velocity VelocityProvider::update(double now_s) {
  // The wheels stand still when the lease ends: the ramp down begins as late as the
  // acceleration limits allow (from the target: a velocity still ramping up stops sooner).
  if (const double ramp_down_s = end_s_ - stopping_time_s(target_);
      state_ == MotionState::Leased && now_s >= ramp_down_s) {
    ramp(std::max(ramp_down_s, ramped_at_s_));
    target_ = {};
    state_ = MotionState::Idle;
    stop_reason_ = "lease ended";
  }
  ramp(now_s);
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
