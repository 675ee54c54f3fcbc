// Application layer (robot): velocities for a real ROS 2 robot, published over DDS.
//
// ROS 2 topics are plain DDS, so the agent drives a TurtleBot3 without ROS installed: it
// writes the DDS topic "rt/<name>" with the DDS types ROS 2 generates for geometry_msgs
// (common/ros2/ros2_msgs.idl), through CycloneDDS's C API. TurtleBot3 on Jazzy subscribes to cmd_vel as
// TwistStamped, on Humble as Twist; it reads only linear.x and angular.z, so the other
// components go out as 0. The QoS is the one turtlebot3_node subscribes with (reliable,
// volatile, keep-last 10), and the data representation is pinned to XCDR1, the only one
// ROS 2's middlewares accept: a writer offering XCDR2 never matches and says nothing.
// The domain follows ROS: the one given, else ROS_DOMAIN_ID, else 0. Which network
// interface DDS uses is CycloneDDS's own configuration (CYCLONEDDS_URI).
//
// Nothing on the robot stops the wheels when cmd_vel stops arriving: the last velocity
// persists, so publishing a stop before letting go of this object is the caller's job.
// The writer carries ros2::kAgentCmdVelUserData, by which the sender's ROS 2 bridge knows the
// robot's output from an operator's cmd_vel on the same domain.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "cmd_vel/velocity.h"
#include "ros2/dds_support.h"

namespace dtmf::agent {

using ros2::DdsError;  // every failure below throws it

struct DdsOptions {
  std::string topic = "cmd_vel";  // the ROS name; "/cmd_vel" is the same topic
  bool stamped = true;            // TwistStamped (Jazzy) or Twist (Humble)
  std::optional<int> domain_id;   // else ROS_DOMAIN_ID, else 0
  std::string frame_id;           // header.frame_id of TwistStamped
};

using ros2::dds_topic_name;

class DdsCmdVel final : public CmdVelOutput {
 public:
  // Throws DdsError when a bad domain or topic is given, or DDS cannot start.
  explicit DdsCmdVel(const DdsOptions& options = {});
  ~DdsCmdVel() override;
  DdsCmdVel(const DdsCmdVel&) = delete;
  DdsCmdVel& operator=(const DdsCmdVel&) = delete;

  // Throws DdsError when the write fails.
  void publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) override;

  // Subscribers matched right now (what discovery has found so far).
  int matched_subscribers() const;
  // Until at least `n` subscribers are matched; false if `timeout` passes first.
  bool wait_for_subscribers(int n, std::chrono::milliseconds timeout) const;

  int domain_id() const;
  std::string topic_name() const;  // the DDS topic, e.g. "rt/cmd_vel"
  std::string type_name() const;   // the DDS type, e.g. "geometry_msgs::msg::dds_::TwistStamped_"

 private:
  // dds_entity_t, kept as its underlying type so that this header needs no DDS headers.
  using Entity = std::int32_t;

  DdsOptions options_;
  Entity participant_ = 0;
  Entity topic_ = 0;
  Entity writer_ = 0;
};

}  // namespace dtmf::agent
