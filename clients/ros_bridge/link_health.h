// A robot's link health as ROS 2's diagnostics report it (diagnostic_msgs/DiagnosticStatus):
// a level, one line, and key-values, worked out from what the robot's Teleop stream says.
//
//   OK     the robot answers every frame (or no frame has been sent to it yet);
//   WARN   answers were lost: fewer frames answered than sent over the server's window;
//   ERROR  the robot stopped answering: kErrorUnanswered frames in a row without an answer.
//
// Only the Teleop stream puts frames on the air for this robot, so health is measured while
// the bridge drives it; between drives the last measurement is kept, and said to be old.
// Pure logic: the caller gives the time (ms on a steady clock).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "teleop_plan.h"

namespace dtmf::ros_bridge {

// diagnostic_msgs/DiagnosticStatus's levels.
enum class HealthLevel : std::uint8_t { Ok = 0, Warn = 1, Error = 2, Stale = 3 };

// One TeleopResponse, as far as health goes.
struct LinkReading {
  bool answered = false;    // its event is an ACK or a NACK: the robot answered a frame
  bool unanswered = false;  // its event is NO_ANSWER
  double link_quality = 1;  // answers heard per frame sent over the window (0..1)
  unsigned frames_in_window = 0;
  double window_s = 0;
  double response_time_ms = 0;  // the last confirmed frame's
  double lease_s = 0;
  double lease_left_s = 0;
  std::optional<Twist> confirmed;  // the velocity the robot confirmed, if it has
};

struct HealthReport {
  HealthLevel level = HealthLevel::Ok;
  std::string message;
  std::vector<std::pair<std::string, std::string>> values;
};

class LinkHealth {
 public:
  static constexpr int kErrorUnanswered = 3;

  void on_reading(const LinkReading& reading, double now_ms);
  HealthReport report(StreamState stream, double now_ms) const;

 private:
  std::optional<LinkReading> last_;
  std::optional<double> last_answer_ms_;
  std::optional<double> last_reading_ms_;
  int unanswered_in_a_row_ = 0;
};

}  // namespace dtmf::ros_bridge
