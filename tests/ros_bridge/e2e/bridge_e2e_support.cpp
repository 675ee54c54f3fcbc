#include "ros_bridge/e2e/bridge_e2e_support.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace dtmf::test_support {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

BridgeSystem BridgeSystem::from_environment() {
  const char* state = std::getenv("DTMF_E2E_STATE");
  const char* domain = std::getenv("ROS_DOMAIN_ID");
  const char* server = std::getenv("DTMF_SERVER");
  if (state == nullptr || domain == nullptr) {
    throw std::runtime_error(
        "DTMF_E2E_STATE and ROS_DOMAIN_ID unset: run through tests/ros_bridge/e2e/run_bridge_e2e.sh");
  }
  return {state, std::atoi(domain), server != nullptr ? server : "localhost:50051"};
}

RobotCmdVel::RobotCmdVel(const BridgeSystem& system, const std::string& ros_topic)
    : subscriber_(std::make_unique<CmdVelSubscriber>(system.domain, "rt/" + ros_topic, true)) {}

std::optional<ReceivedCmdVel> RobotCmdVel::first_after(Clock::time_point since,
                                                       const std::function<bool(const ReceivedCmdVel&)>& accept,
                                                       std::chrono::milliseconds timeout) const {
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    for (const ReceivedCmdVel& v : after(since)) {
      if (accept(v)) return v;
    }
    if (Clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::vector<ReceivedCmdVel> RobotCmdVel::after(Clock::time_point since) const {
  std::vector<ReceivedCmdVel> found;
  for (const ReceivedCmdVel& v : subscriber_->samples()) {
    if (v.from_agent && v.received > since) found.push_back(v);
  }
  return found;
}

bool is_stopped(const ReceivedCmdVel& v) { return v.linear.x == 0 && v.angular.z == 0; }

bool at_velocity(const ReceivedCmdVel& v, double linear_mps, double angular_radps) {
  constexpr double kHalfLinearStepMps = 0.22 / 2047 / 2 + 1e-9;
  constexpr double kHalfAngularStepRadps = 2.84 / 127 / 2 + 1e-9;
  return std::abs(v.linear.x - linear_mps) <= kHalfLinearStepMps &&
         std::abs(v.angular.z - angular_radps) <= kHalfAngularStepRadps;
}

double ms_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

Pose pose_of(const BridgeSystem& system, const std::string& robot) {
  const std::string log = read_file(system.state_dir + "/agent" + robot.substr(robot.size() - 1) + ".log");
  static const std::regex line(R"(sim: (\w+) at t=[\d.]+ s: x=(-?[\d.]+) m y=(-?[\d.]+) m heading=(-?[\d.]+) deg)");
  Pose pose;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator(); ++it) {
    pose = {std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4]), (*it)[1] == "stopped", pose.lines + 1};
  }
  return pose;
}

int bridge_log_count(const BridgeSystem& system, const std::string& text) {
  std::istringstream log(read_file(system.state_dir + "/ros-bridge.log"));
  int count = 0;
  for (std::string line; std::getline(log, line);) count += line.find(text) != std::string::npos;
  return count;
}

pid_t pid_of(const BridgeSystem& system, const std::string& name) {
  const std::string text = read_file(system.state_dir + "/" + name + ".pid");
  if (text.empty()) throw std::runtime_error("no " + name + ".pid in " + system.state_dir);
  return static_cast<pid_t>(std::stol(text));
}

double cpu_seconds(pid_t pid) {
  // /proc/PID/stat: fields 14 and 15 are utime and stime in clock ticks; the command name
  // (field 2) is in parentheses and may hold spaces, so fields are counted after its ')'.
  const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
  std::istringstream rest(stat.substr(stat.rfind(')') + 2));
  std::string field;
  long ticks = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i >= 14) ticks += std::stol(field);
  }
  return static_cast<double>(ticks) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& stdout_path) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  const int rc = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
}

void ChildProcess::terminate() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  ::waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

ChildProcess::~ChildProcess() { kill9(); }

void ChildProcess::kill9() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

std::int64_t unix_ms_now() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

AirWatch::AirWatch(const std::string& dtmfctl, const std::string& server, const std::string& path)
    : path_(path), watch_({dtmfctl, "--server", server, "--json", "watch"}, path) {
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the stream set up
}

int AirWatch::frames_played(std::int64_t from_unix_ms, std::int64_t to_unix_ms, const std::string& robot) {
  watch_.terminate();
  std::ifstream in(path_);
  int frames = 0;
  for (std::string line; std::getline(in, line);) {
    // dtmfctl --json keeps the proto's field names; an int64 is a string in proto3's JSON.
    const nlohmann::json m = nlohmann::json::parse(line, nullptr, false);
    if (m.is_discarded() || !m.contains("frame_played")) continue;
    const std::int64_t t = std::stoll(m.value("time_unix_ms", std::string("0")));
    const auto robots = m["frame_played"].value("robots", std::vector<std::string>{});
    const bool for_robot = robot.empty() || std::find(robots.begin(), robots.end(), robot) != robots.end();
    frames += for_robot && t >= from_unix_ms && t <= to_unix_ms;
  }
  return frames;
}

}  // namespace dtmf::test_support
