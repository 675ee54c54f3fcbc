// Test helper: the programs as background processes, started through the shell as a user
// would start them, and stopped for sure before the next test starts its own (two agents
// on one air would both hear and log every chord).
#pragma once

#include <signal.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "run_command.h"
#include "wait_for.h"

namespace dtmf::test_support {

// Starts `command` in the background, stdout discarded, stderr to `log`; returns its pid.
inline int start_process(const std::string& command, const std::string& log) {
  return std::stoi(run_command(command + " > /dev/null 2> " + log + " & echo $!").out);
}

// Alive and not a zombie waiting for init to reap it.
inline bool process_running(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto state_at = line.rfind(')') + 2;
  return state_at < line.size() && line[state_at] != 'Z';
}

// SIGTERM (or `signal`), then SIGKILL if it is still there after 10 s; returns once gone.
inline void stop_process(int pid, int signal = SIGTERM) {
  if (pid <= 0) return;
  ::kill(pid, signal);
  const auto gone = [pid] { return !process_running(pid); };
  if (wait_until(gone, std::chrono::seconds(10))) return;
  ::kill(pid, SIGKILL);
  wait_until(gone, std::chrono::minutes(1));  // SIGKILL cannot be refused: the kernel takes it down
}

// Until `dtmfctl health` answers on port, for at most 15 s of wall time; false if it never
// does. A deadline rather than a count of tries: each try against a server that died at
// start (say, on a database error) takes seconds, and a hundred of them outlasted ctest's
// timeout, which then killed the test before it could stop the processes it had started.
inline bool wait_healthy(const std::string& dtmfctl, int port) {
  return wait_until(
      [&] { return run_command(dtmfctl + " health --server 127.0.0.1:" + std::to_string(port)).exit_code == 0; },
      std::chrono::seconds(15), std::chrono::milliseconds(100));
}

// Until the robot confirms a Stop sent through the air (`dtmfctl stop` exits 0), for at most
// `deadline`: the sender's chords reach the robot and its answer comes back. The readiness of
// a live system, rather than a fixed wait for its new audio streams to settle (in their first
// seconds they once delivered sound irregularly: chords sent at once were heard late, and
// once twice). It puts a Stop on air, and its frames in the database.
inline bool wait_robot_answers(const std::string& dtmfctl, int port,
                               std::chrono::milliseconds deadline = std::chrono::seconds(60)) {
  return wait_until(
      [&] {
        return run_command(dtmfctl + " --server 127.0.0.1:" + std::to_string(port) + " stop < /dev/null").exit_code ==
               0;
      },
      deadline, std::chrono::milliseconds(100));
}

}  // namespace dtmf::test_support
