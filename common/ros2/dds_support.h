// What every ROS 2 endpoint of ours needs over plain DDS (CycloneDDS's C API), on the robot
// (the agent's cmd_vel) and on the sender (the ROS 2 bridge).
//
// ROS 2 topics are plain DDS: the ROS topic "cmd_vel" is the DDS topic "rt/cmd_vel", and the
// domain is the one given, else ROS_DOMAIN_ID, else 0, as ROS itself chooses it. Which network
// interface DDS uses is CycloneDDS's own configuration (CYCLONEDDS_URI). Every failure throws
// DdsError naming the step, Cyclone's error and what to check.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dtmf::ros2 {

// A DDS call failed. what() names the step and Cyclone's error text, and what to check.
class DdsError : public std::runtime_error {
 public:
  DdsError(const std::string& message, int retcode) : std::runtime_error(message), retcode_(retcode) {}
  int retcode() const { return retcode_; }  // a DDS_RETCODE_*

 private:
  int retcode_;
};

// Above this, DDS's default port mapping (7400 + 250 * domain + ...) leaves the 16-bit
// port range; ROS 2 documents the same bound.
inline constexpr int kMaxDomainId = 232;

// The user data the agent's cmd_vel writer carries: the sender's bridge, which reads cmd_vel
// on the same domain, knows the robot's own output by it and never sends it back.
inline constexpr std::string_view kAgentCmdVelUserData = "dtmf-teleop agent cmd_vel";

// `who` starts the message ("DdsCmdVel: creating ... failed: <Cyclone's text>. <hint>").
[[noreturn]] void dds_fail(std::string_view who, const std::string& step, int retcode, const std::string& hint);

// The domain given, else ROS_DOMAIN_ID (empty is unset, as in ROS), else 0. Throws DdsError
// for a negative one or an ROS_DOMAIN_ID that is not a number.
int resolve_domain(std::string_view who, const std::optional<int>& given);

// The DDS topic ROS 2 uses for a topic name: "cmd_vel" and "/cmd_vel" are "rt/cmd_vel".
std::string dds_topic_name(std::string_view ros_topic);

// A participant on `domain` (an int32 dds_entity_t). The error says why, with the port
// arithmetic for a domain above kMaxDomainId.
std::int32_t create_participant(std::string_view who, int domain);

struct RosTime {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};
RosTime ros_time(std::chrono::system_clock::time_point t);

// The DDS name and type name of a topic.
std::string topic_name_of(std::int32_t topic);
std::string type_name_of(std::int32_t topic);

}  // namespace dtmf::ros2
