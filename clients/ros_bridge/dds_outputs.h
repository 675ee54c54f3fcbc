// What the bridge writes to ROS 2 over DDS: /diagnostics (diagnostic_msgs/DiagnosticArray,
// one status per robot, as rqt_robot_monitor and diagnostic_aggregator read it) and each
// robot's cmd_vel_confirmed (TwistStamped: the velocity the robot confirmed it executes).
// Writers are RELIABLE, VOLATILE, KEEP_LAST 10, XCDR1, as ROS 2 publishes by default.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "bridge_topics.h"
#include "link_health.h"

namespace dtmf::ros_bridge {

struct RobotHealth {
  std::string robot;
  HealthReport report;
};

class DdsOutputs {
 public:
  // Writers in the given participant (dds_inputs.h). Throws ros2::DdsError when DDS refuses one.
  DdsOutputs(std::int32_t participant, const BridgeTopics& topics);

  void publish_diagnostics(const std::vector<RobotHealth>& robots, std::chrono::system_clock::time_point stamp);
  void publish_confirmed(std::size_t robot, Twist confirmed, std::chrono::system_clock::time_point stamp);

 private:
  std::int32_t diagnostics_writer_ = 0;
  std::vector<std::int32_t> confirmed_writers_;  // by robot index
};

}  // namespace dtmf::ros_bridge
