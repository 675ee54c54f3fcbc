// Application layer (robot): a robot that stops even when the agent dies.
//
// A TurtleBot3 keeps its last cmd_vel for ever: turtlebot3_node has no timeout, and it keeps
// the OpenCR board's heartbeat going. So if dtmf-agent crashes or is SIGKILLed while the
// robot moves, nothing of the agent's own can stop it. The guard is a second process,
// started by the agent with its own DDS writer (discovered and matched while the agent
// runs) and the read end of a pipe whose write end only the agent holds. However the agent
// ends, the kernel closes that end and the guard's read() returns. An agent that ends
// normally has stopped the robot itself and writes one byte first, standing the guard down;
// without that byte the guard publishes zero on cmd_vel at once, then exits. The same binary serves a person who needs
// the robot stopped now: `dtmf-agent --stop-robot` publishes zero and exits.
#pragma once

#include <sys/types.h>
#include <chrono>
#include <string>

#include "cmd_vel/dds_cmd_vel.h"

namespace dtmf::agent {

// How many zeros a stop publishes, and how far apart: more than one, because a reliable
// writer's first sample can still be on its way to a subscriber that matched a moment ago.
inline constexpr int kStopRepeats = 3;
inline constexpr std::chrono::milliseconds kStopRepeatGap{50};

// The agent's side: spawns `program --stop-robot-when-closed 3 <DDS flags>` and holds the
// pipe. Destroying it (a normal exit, after the agent's own zero) stands the guard down and
// waits for it to finish. Throws std::runtime_error if the guard cannot be started (the
// agent must not drive unguarded).
class StopGuard {
 public:
  StopGuard(const std::string& program, const DdsOptions& options, const std::string& message);
  ~StopGuard();
  StopGuard(const StopGuard&) = delete;
  StopGuard& operator=(const StopGuard&) = delete;
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int write_fd_ = -1;
};

// The guard's side: a DDS writer now, then block until `fd` reads end-of-file, then stop
// the robot unless the agent stood it down. SIGINT and SIGTERM are held back meanwhile
// (systemd's stop reaches every process of the service at once; the guard must outlive the
// agent to see how it ended). Returns the exit code.
int guard_until_closed(int fd, const DdsOptions& options);

// `--stop-robot`: waits up to `discovery` for a cmd_vel subscriber, publishes zero
// kStopRepeats times and returns 0, or 1 (after publishing anyway) if none was found.
int stop_robot_now(const DdsOptions& options, std::chrono::milliseconds discovery);

}  // namespace dtmf::agent
