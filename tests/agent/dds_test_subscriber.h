// Test helper: a ROS 2-like cmd_vel subscriber, to check what DdsCmdVel puts on the wire.
//
// It reads a DDS topic (the DDS name, e.g. "rt/cmd_vel", so that the publisher's naming is
// under test too) with the same generated ROS 2 types and the QoS turtlebot3_node uses:
// reliable, volatile, keep-last 10, XCDR1 only, as ROS 2's middlewares accept. Samples are
// taken in CycloneDDS's listener thread and kept, with the local time they arrived, for
// the test thread to wait for and inspect.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace dtmf::test_support {

struct ReceivedCmdVel {
  struct Vector3 {
    double x = 0, y = 0, z = 0;
  };
  Vector3 linear;
  Vector3 angular;
  // The header; zero and empty for a bare Twist.
  std::int32_t stamp_sec = 0;
  std::uint32_t stamp_nanosec = 0;
  std::string frame_id;
  std::chrono::steady_clock::time_point received;
  // Written by a dtmf-agent (its writer carries ros2::kAgentCmdVelUserData): the robot's
  // output, as against an operator's cmd_vel on the same topic (the ROS 2 bridge's input).
  bool from_agent = false;
};

class CmdVelSubscriber {
 public:
  // Throws std::runtime_error when DDS cannot start.
  CmdVelSubscriber(int domain_id, const std::string& dds_topic, bool stamped);
  ~CmdVelSubscriber();
  CmdVelSubscriber(const CmdVelSubscriber&) = delete;
  CmdVelSubscriber& operator=(const CmdVelSubscriber&) = delete;

  // Until at least `count` samples have arrived; false if `timeout` passes first.
  bool wait_for(std::size_t count, std::chrono::milliseconds timeout) const;
  std::vector<ReceivedCmdVel> samples() const;
  int matched_publishers() const;

 private:
  static void on_data_available(std::int32_t reader, void* self);
  void take(std::int32_t reader);
  bool written_by_agent(std::int32_t reader, std::uint64_t publication) const;

  bool stamped_;
  std::int32_t participant_ = 0;  // dds_entity_t
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  std::vector<ReceivedCmdVel> samples_;
  std::int32_t reader_ = 0;
};

}  // namespace dtmf::test_support
