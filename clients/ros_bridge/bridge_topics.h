// The ROS 2 topics the bridge reads and writes, from the robots the server drives.
//
// One robot: `cmd_vel`, as teleop_twist_keyboard, teleop_twist_joy and Nav2 publish by
// default. Several: one per robot, namespaced by its name (`robot2/cmd_vel`), so that each
// tool drives only the robot it is pointed at (`--ros-args -r cmd_vel:=robot2/cmd_vel`).
// Always: `stop_every_robot` (std_msgs/Empty: any message stops every robot in the room),
// `diagnostics` (the link's health), and each robot's `cmd_vel_confirmed` (TwistStamped: the
// velocity the robot confirmed it executes).
#pragma once

#include <string>
#include <vector>

namespace dtmf::ros_bridge {

struct RobotTopics {
  std::string robot;  // its name, as the server knows it
  std::string cmd_vel;
  std::string cmd_vel_confirmed;
};

struct BridgeTopics {
  std::vector<RobotTopics> robots;
  std::string stop_every_robot = "stop_every_robot";
  std::string diagnostics = "diagnostics";
};

// Throws std::invalid_argument when there is no robot, or a name is no ROS name (a letter,
// then letters, digits and underscores), quoting it.
BridgeTopics bridge_topics(const std::vector<std::string>& robot_names);

}  // namespace dtmf::ros_bridge
