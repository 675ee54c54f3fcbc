// cmd_vel output `sim`: a simulated TurtleBot3 for people without one.
//
// Unicycle kinematics: the robot turns at angular.z and moves forward at linear.x, both
// held within the model's limits (as turtlebot3_node does), integrated between publishes
// with the exact arc. It reports its pose once a second while moving and when it stops.
#pragma once

#include <functional>
#include <string>

#include "cmd_vel/velocity.h"
#include "command/robot_model.h"

namespace dtmf::agent {

struct Pose {
  double x_m = 0;
  double y_m = 0;
  double theta_rad = 0;  // counter-clockwise from +x
};

class SimTurtlebot : public CmdVelOutput {
 public:
  using Report = std::function<void(const std::string&)>;
  SimTurtlebot(command::RobotModel model, Report report);
  void publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) override;
  const Pose& pose() const { return pose_; }
  double distance_m() const { return distance_m_; }

 private:
  void say(double audio_ms, const char* what);

  command::RobotModel model_;
  Report report_;
  Pose pose_;
  Velocity velocity_;  // in force since last_ms_
  double last_ms_ = -1;
  double last_report_ms_ = -1e9;
  double distance_m_ = 0;
};

}  // namespace dtmf::agent
