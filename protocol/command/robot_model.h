// Command abstraction layer: what the TurtleBot3 models can do, and velocities in their
// units (m/s, rad/s) as the fractions a Velocity command carries.
//
// Limits from the TurtleBot3 specifications (and turtlebot3_teleop): Burger 0.22 m/s and
// 2.84 rad/s, Waffle / Waffle Pi 0.26 m/s and 1.82 rad/s. Acceleration limits (the robot
// ramps towards every new velocity, so a lost frame or a reversal never jerks the wheels):
// turtlebot3's navigation default of 2.5 m/s² for the linear axis; 25 rad/s² for the angular
// one (its navigation's 3.2 rad/s² would take 0.9 s to stop a Burger turning at full rate),
// so that when a lease ends the wheels are still within 0.12 s on either model and the
// robot stops within its lease + 0.2 s (docs/protocol.md §10, "Velocity and its lease").
#pragma once

#include <string>
#include <string_view>

#include "command/command.h"

namespace dtmf::command {

struct RobotModel {
  std::string name;
  double max_linear_mps;
  double max_angular_radps;
  double linear_accel_mps2 = 2.5;
  double angular_accel_rps2 = 25.0;
};

const RobotModel& burger();
const RobotModel& waffle();
// "burger", "waffle" (also "waffle_pi"); throws std::invalid_argument naming the choices.
const RobotModel& robot_model_by_name(std::string_view name);

// A Velocity for `model` from speeds in its units. Throws ParameterError naming linear_mps,
// angular_radps or lease_s with the allowed range.
Velocity velocity_command(const RobotModel& model, double linear_mps, double angular_radps, double lease_s);
// What a Velocity asks of `model`, in m/s and rad/s.
double linear_mps(const RobotModel& model, const Velocity& velocity);
double angular_radps(const RobotModel& model, const Velocity& velocity);

}  // namespace dtmf::command
