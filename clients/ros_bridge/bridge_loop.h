// The bridge's loop: ROS 2's cmd_vel in (dds_inputs.h), each robot's Teleop stream driven by
// its plan (teleop_plan.h), the link's health and the confirmed velocity out (dds_outputs.h).
//
// One thread runs it, waiting in one place (DDS's waitset) for a message, a gRPC event
// (bridge_events.h) or the next deadline the input and the plans name; nothing polls. A
// robot's input times out after `timeout_ms` (twist_mux's input timeout), and then, as on an
// explicit zero, the bridge sends the zero at once. A message on stop_every_robot sends the
// stop for every robot, which ends every stream; each then holds until its input is zero.
// stop() (from any thread) makes every input zero: run() returns once every robot the bridge
// drove has confirmed its stop or its lease has lapsed, or after kLeaveMs at the latest.
#pragma once

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "bridge_events.h"
#include "bridge_topics.h"
#include "dds_inputs.h"
#include "dds_outputs.h"
#include "link_health.h"
#include "stop_call.h"
#include "teleop_call.h"
#include "teleop_plan.h"
#include "twist_input.h"

namespace dtmf::ros_bridge {

struct BridgeRobot {
  std::string name;
  TwistLimits limits;
};

struct BridgeSettings {
  std::vector<BridgeRobot> robots;
  int domain = 0;
  double timeout_ms = 500;
  double lease_s = 1.0;
  std::string profile = "fast";
  std::string token;
  double diagnostics_period_ms = 1000;  // ROS's diagnostic_updater publishes at 1 Hz
};

class BridgeLoop {
 public:
  static constexpr double kLeaveMs = 5000;  // stop(): the longest run() waits for the robots

  // Throws ros2::DdsError when DDS cannot start, std::invalid_argument for a robot name that
  // cannot name a topic.
  BridgeLoop(std::shared_ptr<grpc::Channel> channel, BridgeSettings settings);
  ~BridgeLoop();

  void run();
  void stop();  // any thread
  const BridgeTopics& topics() const { return topics_; }
  int domain() const { return settings_.domain; }

 private:
  struct Robot {
    std::string name;
    TwistInput input;
    TeleopPlan plan;
    LinkHealth health;
    std::unique_ptr<TeleopCall> call;
    std::uint64_t call_id = 0;
    std::optional<Twist> confirmed;
    std::string last_failure;  // said once until it changes
  };

  double now_ms() const;
  void take_inputs(double now_ms);
  void handle(const BridgeEvent& event, double now_ms);
  void handle_stream_end(Robot& robot, const grpc::Status& status, double now_ms);
  void drive(std::size_t index, double now_ms);
  void publish_diagnostics(double now_ms);
  bool everything_stopped() const;
  double next_wake_ms(double now_ms, double leave_at_ms) const;

  std::unique_ptr<v1::TeleopService::Stub> stub_;
  BridgeSettings settings_;
  BridgeTopics topics_;
  DdsInputs inputs_;
  DdsOutputs outputs_;
  BridgeEvents events_;
  std::vector<Robot> robots_;
  std::unique_ptr<StopCall> stop_call_;
  std::uint64_t next_call_id_ = 1;
  double next_diagnostics_ms_ = 0;
  std::atomic<bool> leaving_{false};
};

}  // namespace dtmf::ros_bridge
