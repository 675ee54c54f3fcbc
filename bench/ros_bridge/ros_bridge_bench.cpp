// dtmf-bench-ros-bridge: issue 62's targets for dtmf-ros-bridge, measured on a running system
// (bench/ros_bridge/run_ros_bridge_bench.sh starts scripts/quickstart, one robot through the
// seminar room both ways, keyed or not, with the bridge), from outside, as a ROS 2 user sees it:
//
//   changes  a teleop_twist_keyboard-like publisher (Twist, RELIABLE, 10 Hz) changes its
//            velocity N times: each change's first message → the robot's cmd_vel at it (the
//            agent's own DDS writer). The first, which opens the stream, is kept apart.
//   stops    the publisher goes silent (every other one) or, a Fast DDS publisher, is killed
//            with -9 mid-drive: the last message (the kill) → the robot's cmd_vel zero.
//   nav2     a Nav2-like stream (Twist at 20 Hz) for S seconds: the frames the sender plays
//            for the robot meanwhile (dtmfctl watch --json), and the lapses: samples of the
//            robot's cmd_vel at zero after it first moved, while the stream runs.
//
// Prints each figure and writes them as JSON (--json).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "ros_bridge/e2e/bridge_e2e_support.h"
#include "ros_bridge/e2e/ros2_test_endpoints.h"

namespace {

using namespace dtmf::test_support;
using namespace std::chrono_literals;
using nlohmann::json;

struct Options {
  std::string state_dir, topic = "cmd_vel", fastdds, dtmfctl, server = "localhost:50051", json_path;
  int domain = 0, changes = 40, stops = 10;
  double nav2_s = 30;
  bool keyed = true;
};

json summary(std::vector<double> ms) {
  if (ms.empty()) return nullptr;
  std::sort(ms.begin(), ms.end());
  const auto at = [&](double p) {
    return ms[std::min(ms.size() - 1, static_cast<std::size_t>(p * (ms.size() - 1) + 0.5))];
  };
  return {{"median", at(0.5)}, {"p95", at(0.95)}, {"max", ms.back()}, {"count", ms.size()}};
}

double stopped_after(const RobotCmdVel& robot, Clock::time_point since) {
  const auto zero = robot.first_after(since, is_stopped, 5000ms);
  return zero ? ms_between(since, zero->received) : 1e9;
}

json measure_changes(const Options& o, TwistPublisher& keys, const RobotCmdVel& robot) {
  // Distinct velocities within a Burger's limits, each differing from the one before.
  const std::vector<std::pair<double, double>> values{{0.10, 0.0}, {0.15, 0.3},  {0.05, -0.4}, {0.12, 0.0},
                                                      {0.08, 0.6}, {0.18, -0.2}, {0.03, 0.0},  {0.11, 0.45}};
  std::vector<double> ms;
  double opening_ms = 0;
  for (int i = 0; i <= o.changes; ++i) {
    const auto [v, w] = values[static_cast<std::size_t>(i) % values.size()];
    const auto at = Clock::now();
    keys.hold(v, w, 1200ms, 100ms);
    const auto seen = robot.first_after(
        at, [&](auto& s) { return at_velocity(s, v, w); }, 100ms);
    const double delay = seen ? ms_between(at, seen->received) : 1e9;
    if (i == 0) {
      opening_ms = delay;
    } else {
      ms.push_back(delay);
    }
  }
  keys.publish(0, 0);
  std::this_thread::sleep_for(1500ms);
  json out = summary(ms);
  out["opening_ms"] = opening_ms;
  std::printf("changes: median %.0f ms, p95 %.0f ms over %zu; the first (opening the stream) %.0f ms\n",
              out["median"].get<double>(), out["p95"].get<double>(), ms.size(), opening_ms);
  return out;
}

json measure_stops(const Options& o, TwistPublisher& keys, const RobotCmdVel& robot) {
  json trials = json::array();
  for (int i = 0; i < o.stops; ++i) {
    const bool kill = i % 2 == 1;
    Clock::time_point last;
    if (kill) {
      ChildProcess fast({o.fastdds, "--domain", std::to_string(o.domain), "--topic", o.topic, "--linear-mps", "0.1",
                         "--rate-hz", "10", "--duration-s", "60"});
      robot.first_after(
          Clock::now(), [](auto& s) { return at_velocity(s, 0.1, 0); }, 10000ms);
      std::this_thread::sleep_for(1000ms);
      last = Clock::now();
      fast.kill9();
    } else {
      last = keys.hold(0.1, 0, 2000ms, 100ms);
    }
    const double ms = stopped_after(robot, last);
    trials.push_back({{"kind", kill ? "killed -9 (Fast DDS)" : "silent"}, {"ms", ms}});
    std::printf("stop %d (%s): %.0f ms\n", i + 1, kill ? "killed -9" : "silent", ms);
    std::this_thread::sleep_for(1000ms);
  }
  return trials;
}

json measure_nav2(const Options& o, TwistPublisher& nav2, const RobotCmdVel& robot) {
  AirWatch air(o.dtmfctl, o.server, o.state_dir + "/bench-watch.jsonl");
  const auto start = Clock::now();
  const std::int64_t start_unix_ms = unix_ms_now();
  nav2.hold(0.1, 0.2, std::chrono::milliseconds(static_cast<long>(o.nav2_s * 1000)), 50ms);
  const std::int64_t end_unix_ms = unix_ms_now();
  const auto end = Clock::now();
  nav2.publish(0, 0);
  std::this_thread::sleep_for(1000ms);
  // Frames played from when the robot first moved to the stream's end.
  const auto moving = robot.first_after(
      start, [](auto& s) { return at_velocity(s, 0.1, 0.2); }, 100ms);
  const std::int64_t from_unix_ms = start_unix_ms + (moving ? std::llround(ms_between(start, moving->received)) : 0);
  const int frames = air.frames_played(from_unix_ms, end_unix_ms);
  int lapses = 0;
  for (const ReceivedCmdVel& s : robot.after(moving ? moving->received : end))
    lapses += s.received < end && is_stopped(s);
  const double seconds = static_cast<double>(end_unix_ms - from_unix_ms) / 1000;
  std::printf("nav2: %d frames in %.1f s (%.2f a second), %d lapses\n", frames, seconds, frames / seconds, lapses);
  return {{"seconds", seconds}, {"frames", frames}, {"frames_per_s", frames / seconds}, {"lapses", lapses}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-ros-bridge: dtmf-ros-bridge's latencies, stops and renewals on a running system");
  Options o;
  app.add_option("--state-dir", o.state_dir, "the quickstart's state directory")->required();
  app.add_option("--domain", o.domain, "ROS domain")->required();
  app.add_option("--topic", o.topic, "the robot's cmd_vel topic")->capture_default_str();
  app.add_option("--fastdds-publisher", o.fastdds, "tests/interop/fastdds's publisher")->required();
  app.add_option("--dtmfctl", o.dtmfctl, "dtmfctl, for watch")->required();
  app.add_option("--server", o.server, "dtmf-server")->capture_default_str();
  app.add_option("--changes", o.changes, "velocity changes")->capture_default_str();
  app.add_option("--stops", o.stops, "stops (half silent, half killed -9)")->capture_default_str();
  app.add_option("--nav2-s", o.nav2_s, "seconds of a 20 Hz stream")->capture_default_str();
  app.add_option("--keyed", o.keyed, "whether the system runs with keys (recorded)")->capture_default_str();
  app.add_option("--json", o.json_path, "where to write the figures")->required();
  CLI11_PARSE(app, argc, argv);

  const BridgeSystem system{o.state_dir, o.domain, o.server};
  RobotCmdVel robot(system, o.topic);
  TwistPublisher keys(o.domain, o.topic, {.stamped = false, .reliable = true});
  if (!keys.wait_for_readers(1, 10s)) {
    std::fprintf(stderr, "dtmf-bench-ros-bridge: no bridge reads %s on domain %d\n", o.topic.c_str(), o.domain);
    return 1;
  }
  char measured[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(measured, sizeof measured, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  json out{{"keyed", o.keyed}, {"timeout_ms", 500}, {"lease_ms", 1000}, {"measured_utc", measured}};
  out["changes"] = measure_changes(o, keys, robot);
  out["stops"] = measure_stops(o, keys, robot);
  out["nav2"] = measure_nav2(o, keys, robot);
  std::ofstream(o.json_path) << out.dump(2) << "\n";
  return 0;
}
