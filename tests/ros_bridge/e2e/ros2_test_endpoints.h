// Test helpers: ROS 2 endpoints over CycloneDDS's C API, as ROS 2's tools have them, to drive
// and watch dtmf-ros-bridge from outside: a cmd_vel publisher (Twist or TwistStamped,
// RELIABLE like teleop_twist_keyboard or BEST_EFFORT), a std_msgs/Empty publisher (the stop
// for every robot), and a /diagnostics subscriber that keeps each robot's newest status.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace dtmf::test_support {

struct TwistQos {
  bool stamped = false;
  bool reliable = true;  // else BEST_EFFORT
};

class TwistPublisher {
 public:
  // `ros_topic`: "robot1/cmd_vel". Throws std::runtime_error when DDS cannot start.
  TwistPublisher(int domain, const std::string& ros_topic, TwistQos qos);
  ~TwistPublisher();
  TwistPublisher(const TwistPublisher&) = delete;
  TwistPublisher& operator=(const TwistPublisher&) = delete;

  // `frame_id`: a TwistStamped's header.frame_id ("base_link" when not given).
  void publish(double linear_mps, double angular_radps, const std::string& frame_id = "base_link");
  // Publishes (v, w) every `period` for `duration`, as a keyboard's repeat or Nav2's
  // controller does; returns when the last one went out.
  std::chrono::steady_clock::time_point hold(double linear_mps, double angular_radps,
                                             std::chrono::milliseconds duration, std::chrono::milliseconds period);
  // Until `n` readers match (the bridge's); false if `timeout` passes first.
  bool wait_for_readers(int n, std::chrono::milliseconds timeout) const;

 private:
  TwistQos qos_;
  std::int32_t participant_ = 0;
  std::int32_t writer_ = 0;
};

class EmptyPublisher {
 public:
  EmptyPublisher(int domain, const std::string& ros_topic);
  ~EmptyPublisher();
  EmptyPublisher(const EmptyPublisher&) = delete;
  EmptyPublisher& operator=(const EmptyPublisher&) = delete;
  void publish();
  bool wait_for_readers(int n, std::chrono::milliseconds timeout) const;

 private:
  std::int32_t participant_ = 0;
  std::int32_t writer_ = 0;
};

struct ReceivedStatus {
  int level = -1;  // OK 0, WARN 1, ERROR 2, STALE 3
  std::string message;
  std::map<std::string, std::string> values;
  std::chrono::steady_clock::time_point received;
};

class DiagnosticsSubscriber {
 public:
  explicit DiagnosticsSubscriber(int domain);
  ~DiagnosticsSubscriber();
  DiagnosticsSubscriber(const DiagnosticsSubscriber&) = delete;
  DiagnosticsSubscriber& operator=(const DiagnosticsSubscriber&) = delete;

  // The newest status of `robot` (its hardware_id) for which `accept` holds, arrived within
  // `timeout`; level -1 if none came.
  ReceivedStatus wait_for(const std::string& robot, const std::function<bool(const ReceivedStatus&)>& accept,
                          std::chrono::milliseconds timeout) const;
  ReceivedStatus latest(const std::string& robot) const;

 private:
  static void on_data_available(std::int32_t reader, void* self);
  void take(std::int32_t reader);

  std::int32_t participant_ = 0;
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  std::map<std::string, ReceivedStatus> latest_;
};

}  // namespace dtmf::test_support
