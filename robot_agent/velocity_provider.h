// Application layer (robot): the seed's velocity provider (its section 5, Fig. 3).
//
// Commands set a velocity and a state: IDLE (standing), DURATION (moving until an end
// time), CONTINUOUS (moving until the next command). update() is called every publish
// cycle and returns what to publish; it ends a DURATION at its end time and — because
// nothing on a TurtleBot3 stops the wheels when cmd_vel goes quiet — a CONTINUOUS motion
// that has run longer than the safety limit. Inputs: speed 0..100 % of the model's top
// speed, rotation -100..100 % of its top turn rate (positive turns left).
// Pure logic: the caller passes the time (seconds on any steady scale).
#pragma once

#include <optional>
#include <string>

#include "cmd_vel/velocity.h"
#include "command/command.h"
#include "robot_model.h"

namespace dtmf::agent {

enum class MotionState { Idle, Duration, Continuous };
std::string motion_state_name(MotionState state);

class VelocityProvider {
 public:
  // continuous_limit_s: a CONTINUOUS motion stops after this long; 0 disables the limit.
  VelocityProvider(RobotModel model, double continuous_limit_s);

  // A complete command from the command layer, heard at now_s. RESET changes nothing here.
  void apply(const command::Command& command, double now_s);
  // Once per publish cycle: the velocity to publish now.
  Velocity update(double now_s);
  // Stop at once (shutdown).
  void stop();

  MotionState state() const { return state_; }
  Velocity velocity() const { return velocity_; }
  // Why the last automatic stop happened ("duration ended", "continuous limit of 30 s"), once.
  std::optional<std::string> take_stop_reason();

 private:
  Velocity drive(double speed_percent) const;
  Velocity turn(double rotation_percent) const;

  RobotModel model_;
  double continuous_limit_s_;
  MotionState state_ = MotionState::Idle;
  Velocity velocity_;
  double end_s_ = 0;  // DURATION: when to stop; CONTINUOUS: when the safety limit strikes
  std::optional<std::string> stop_reason_;
};

}  // namespace dtmf::agent
