// Application layer (robot): what the TurtleBot3 models can do, for scaling velocities.
//
// Limits from the TurtleBot3 specifications (and turtlebot3_teleop): Burger 0.22 m/s and
// 2.84 rad/s, Waffle / Waffle Pi 0.26 m/s and 1.82 rad/s.
#pragma once

#include <string>
#include <string_view>

namespace dtmf::agent {

struct RobotModel {
  std::string name;
  double max_linear_mps;
  double max_angular_rps;
};

const RobotModel& burger();
const RobotModel& waffle();
// "burger", "waffle" (also "waffle_pi"); throws std::invalid_argument naming the choices.
const RobotModel& robot_model_by_name(std::string_view name);

}  // namespace dtmf::agent
