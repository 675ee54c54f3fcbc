// dtmfctl teleop: turtlebot3_teleop_key's keys as changes to a target velocity. Pure logic.
//
//   w / x   linear speed +0.01 / -0.01 m/s (x past zero reverses)
//   a / d   angular speed +0.1 / -0.1 rad/s (positive turns left)
//   s, space  stop (both zero)
//   e         emergency: stop every robot in the room (the caller sends Stop all_robots and quits)
//   q, Ctrl-C quit (the caller then sends Stop)
// A step never leaves the robot model's limits: it stops at the limit, as turtlebot3_teleop's
// does.
#pragma once

#include "command/robot_model.h"

namespace dtmf::cli {

inline constexpr double kLinearStep_mps = 0.01;
inline constexpr double kAngularStep_radps = 0.1;

struct TeleopTarget {
  double linear_mps = 0;
  double angular_radps = 0;
  bool operator==(const TeleopTarget&) const = default;
};

enum class KeyEffect { None, Changed, Quit, StopEveryRobot };

// Applies `key` (a character, or 3 for Ctrl-C) to `target` within `model`'s limits.
KeyEffect apply_key(int key, TeleopTarget& target, const command::RobotModel& model);

}  // namespace dtmf::cli
