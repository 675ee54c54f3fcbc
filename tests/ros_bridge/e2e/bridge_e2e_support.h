// What the ROS 2 bridge's end-to-end tests read of the whole system that
// run_bridge_e2e.sh starts (scripts/quickstart --robots 3): each robot's cmd_vel as its agent
// publishes it (DDS), its simulated TurtleBot3's pose (the agent's log), the bridge's log, the
// agents' processes, and a publisher in a process of its own (to be killed with -9).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "agent/dds_test_subscriber.h"

namespace dtmf::test_support {

using Clock = std::chrono::steady_clock;

// The quickstart's state directory, the domain, the server: from the environment the runner sets.
struct BridgeSystem {
  std::string state_dir;  // DTMF_E2E_STATE
  int domain = 0;         // ROS_DOMAIN_ID
  std::string server;     // DTMF_SERVER
  static BridgeSystem from_environment();
};

// A robot's cmd_vel as its agent publishes it (TwistStamped; the agent's writer only).
class RobotCmdVel {
 public:
  // `ros_topic`: the agent's cmd_vel, "robot2/cmd_vel" (several robots) or "cmd_vel" (one).
  RobotCmdVel(const BridgeSystem& system, const std::string& ros_topic);
  // The first sample from the agent received after `since` for which `accept` holds, within `timeout`.
  std::optional<ReceivedCmdVel> first_after(Clock::time_point since,
                                            const std::function<bool(const ReceivedCmdVel&)>& accept,
                                            std::chrono::milliseconds timeout) const;
  // Every sample from the agent received after `since`.
  std::vector<ReceivedCmdVel> after(Clock::time_point since) const;

 private:
  std::unique_ptr<CmdVelSubscriber> subscriber_;
};

bool is_stopped(const ReceivedCmdVel& v);
// Within half a VELOCITY step of (linear, angular): 1/2047 of a Burger's 0.22 m/s and 1/127
// of its 2.84 rad/s, the resolution a frame carries a velocity at.
bool at_velocity(const ReceivedCmdVel& v, double linear_mps, double angular_radps);
double ms_between(Clock::time_point from, Clock::time_point to);

struct Pose {
  double x_m = 0, y_m = 0, heading_deg = 0;
  bool stopped = false;  // the line says "stopped"
  int lines = 0;         // pose lines so far
};
// The simulated TurtleBot3's newest pose line in its agent's log.
Pose pose_of(const BridgeSystem& system, const std::string& robot);

// Lines of the bridge's log (stderr) that contain `text`.
int bridge_log_count(const BridgeSystem& system, const std::string& text);
// The process id in STATE/<name>.pid.
pid_t pid_of(const BridgeSystem& system, const std::string& name);
// CPU seconds (user + system) the process has used so far.
double cpu_seconds(pid_t pid);

// A program run in a process of its own; killed with SIGKILL when destroyed if still running.
class ChildProcess {
 public:
  // `stdout_path`: where its standard output goes (empty: this process's).
  explicit ChildProcess(const std::vector<std::string>& argv, const std::string& stdout_path = "");
  ~ChildProcess();
  void kill9();
  void terminate();  // SIGTERM, then waits for it
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
};

// The wall clock in ms since 1970, as WatchAir stamps what it streams.
std::int64_t unix_ms_now();

// The air as the sender plays it: `dtmfctl --json watch` into a file from construction on.
class AirWatch {
 public:
  AirWatch(const std::string& dtmfctl, const std::string& server, const std::string& path);
  // Ends the watch; the frames played for `robot` (empty: for any) between the two wall times.
  int frames_played(std::int64_t from_unix_ms, std::int64_t to_unix_ms, const std::string& robot = "");

 private:
  std::string path_;
  ChildProcess watch_;
};

}  // namespace dtmf::test_support
