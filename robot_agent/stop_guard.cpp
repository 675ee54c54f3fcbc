#include "stop_guard.h"

#include <fcntl.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace dtmf::agent {

namespace {

// The descriptor the guard reads: fixed, so that its command line says which it is.
constexpr int kGuardFd = 3;

void publish_stop(DdsCmdVel& cmd_vel) {
  for (int i = 0; i < kStopRepeats; ++i) {
    if (i > 0) std::this_thread::sleep_for(kStopRepeatGap);
    cmd_vel.publish(Velocity{}, 0, std::chrono::system_clock::now());
  }
}

std::string errno_text() { return std::strerror(errno); }

}  // namespace

StopGuard::StopGuard(const std::string& program, const DdsOptions& options, const std::string& message) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("cannot make the stop guard's pipe: " + errno_text());
  std::vector<std::string> args{
      program, "--stop-robot-when-closed", std::to_string(kGuardFd), "--topic", options.topic, "--message", message};
  if (options.domain_id) args.insert(args.end(), {"--ros-domain-id", std::to_string(*options.domain_id)});
  if (!options.frame_id.empty()) args.insert(args.end(), {"--frame-id", options.frame_id});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  // dup2 clears close-on-exec on the copy: the guard gets the read end as fd 3 and nothing
  // else of ours; the write end stays with the agent alone.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], kGuardFd);
  // Its own process group: a Ctrl-C meant for the agent must not reach the guard first.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int spawned = ::posix_spawn(&pid_, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(fds[0]);
  if (spawned != 0) {
    ::close(fds[1]);
    throw std::runtime_error("cannot start the stop guard (" + program + "): " + std::strerror(spawned));
  }
  write_fd_ = fds[1];
}

StopGuard::~StopGuard() {
  // The agent got here: it has stopped the robot itself. Stand the guard down, so that a
  // normal exit puts no extra zeros on cmd_vel (a stopped robot is stopped either way).
  const char stand_down = 's';
  if (::write(write_fd_, &stand_down, 1) != 1) spdlog::warn("could not stand the stop guard down: {}", errno_text());
  ::close(write_fd_);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
}

int guard_until_closed(int fd, const DdsOptions& options) {
  sigset_t held;
  sigemptyset(&held);
  sigaddset(&held, SIGINT);
  sigaddset(&held, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &held, nullptr);
  DdsCmdVel cmd_vel(options);  // discovery runs while the agent does
  bool stood_down = false;
  char byte;
  ssize_t got;
  do {
    got = ::read(fd, &byte, 1);
    if (got == 1) stood_down = true;
  } while (got > 0 || (got < 0 && errno == EINTR));
  if (stood_down) return 0;  // the agent ended normally, having stopped the robot itself
  publish_stop(cmd_vel);
  spdlog::info("stop guard: the agent has ended; zero published on {}", cmd_vel.topic_name());
  return 0;
}

int stop_robot_now(const DdsOptions& options, std::chrono::milliseconds discovery) {
  DdsCmdVel cmd_vel(options);
  const bool found = cmd_vel.wait_for_subscribers(1, discovery);
  publish_stop(cmd_vel);
  if (!found) {
    spdlog::error(
        "zero published on {} (domain {}), but no subscriber was found within {} ms: is the robot on this "
        "DDS domain and network (ROS_DOMAIN_ID, CYCLONEDDS_URI)?",
        cmd_vel.topic_name(), cmd_vel.domain_id(), discovery.count());
    return 1;
  }
  spdlog::info("zero published on {} (domain {}) to {} subscriber(s)", cmd_vel.topic_name(), cmd_vel.domain_id(),
               cmd_vel.matched_subscribers());
  return 0;
}

}  // namespace dtmf::agent
