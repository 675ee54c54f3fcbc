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
  for (int i = 0; i < 100 && process_running(pid); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (process_running(pid)) ::kill(pid, SIGKILL);
  while (process_running(pid)) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

// Until `dtmfctl health` answers on port, for at most 15 s of wall time; false if it never
// does. A deadline rather than a count of tries: each try against a server that died at
// start (say, on a database error) takes seconds, and a hundred of them outlasted ctest's
// timeout, which then killed the test before it could stop the processes it had started.
inline bool wait_healthy(const std::string& dtmfctl, int port) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  while (std::chrono::steady_clock::now() < deadline) {
    if (run_command(dtmfctl + " health --server 127.0.0.1:" + std::to_string(port)).exit_code == 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

}  // namespace dtmf::test_support
