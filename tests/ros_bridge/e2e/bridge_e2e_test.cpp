// dtmf-ros-bridge end to end, as a ROS 2 user drives it: real DDS publishers on the sender's
// side (Cyclone's C API, and Fast DDS as ROS 2 Jazzy's default middleware), the bridge, the
// server and three real agents on the simulated air (scripts/quickstart --robots 3, keyed),
// and DDS subscribers on each robot's cmd_vel as its agent publishes it. Started by
// run_bridge_e2e.sh. Every robot's agent publishes its own cmd_vel on the very topic the
// bridge reads (robot<k>/cmd_vel, one domain): the loop that must not happen is in place.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <cstdio>
#include <thread>

#include "ros_bridge/e2e/bridge_e2e_support.h"
#include "ros_bridge/e2e/ros2_test_endpoints.h"

namespace dtmf::test_support {
namespace {

using namespace std::chrono_literals;

constexpr double kTimeoutMs = 500;  // the bridge's --timeout-s, as the runner starts it
constexpr double kLeaseMs = 1000;   // its --lease-s
constexpr double kStopBoundMs = kTimeoutMs + kLeaseMs + 200;
constexpr double kBurgerMaxLinearMps = 0.22;
constexpr double kLinearStepMps = 0.22 / 2047 / 2 + 1e-9;  // half a VELOCITY step

class BridgeE2E : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    system_ = BridgeSystem::from_environment();
    for (const char* topic : {"robot1/cmd_vel", "robot2/cmd_vel", "robot3/cmd_vel"}) {
      robots_.emplace_back(new RobotCmdVel(system_, topic));
    }
    diagnostics_ = new DiagnosticsSubscriber(system_.domain);
  }
  static void TearDownTestSuite() {
    for (RobotCmdVel* r : robots_) delete r;
    robots_.clear();
    delete diagnostics_;
  }

  // The time from `since` until the robot's cmd_vel is zero and stays zero for 1 s after.
  static double stop_ms(int robot, Clock::time_point since) {
    const auto stopped = robots_[robot]->first_after(since, is_stopped, std::chrono::milliseconds(5000));
    if (!stopped) return 1e9;
    std::this_thread::sleep_for(1s);
    for (const ReceivedCmdVel& v : robots_[robot]->after(stopped->received)) {
      if (!is_stopped(v)) return 1e9;
    }
    return ms_between(since, stopped->received);
  }

  static inline BridgeSystem system_;
  static inline std::vector<RobotCmdVel*> robots_;
  static inline DiagnosticsSubscriber* diagnostics_ = nullptr;
};

TEST_F(BridgeE2E, AKeyboardLikePublisherDrivesEachKeyAndTheRobotStopsWhenItIsReleased) {
  TwistPublisher keys(system_.domain, "robot1/cmd_vel", {.stamped = false, .reliable = true});
  // What the bridge says the robot confirmed it executes (its writer, not an agent's).
  CmdVelSubscriber confirmed(system_.domain, "rt/robot1/cmd_vel_confirmed", true);
  ASSERT_TRUE(keys.wait_for_readers(1, 10s)) << "the bridge's reader on robot1/cmd_vel";
  const auto forward_at = Clock::now();
  keys.hold(0.1, 0, 2000ms, 100ms);
  const auto left_at = Clock::now();
  const auto released_at = keys.hold(0.1, 0.5, 1500ms, 100ms);

  const auto forward = robots_[0]->first_after(
      forward_at, [](auto& v) { return at_velocity(v, 0.1, 0); }, 100ms);
  const auto left = robots_[0]->first_after(
      left_at, [](auto& v) { return at_velocity(v, 0.1, 0.5); }, 100ms);
  ASSERT_TRUE(forward) << "robot1's cmd_vel never followed the first key";
  ASSERT_TRUE(left) << "robot1's cmd_vel never followed the second key";
  const double stopped_ms = stop_ms(0, released_at);
  std::printf("key -> cmd_vel: %.0f ms, %.0f ms; released -> stopped: %.0f ms (bound %.0f)\n",
              ms_between(forward_at, forward->received), ms_between(left_at, left->received), stopped_ms, kStopBoundMs);
  EXPECT_LT(ms_between(forward_at, forward->received), 1000);
  EXPECT_LT(ms_between(left_at, left->received), 1000);
  EXPECT_LE(stopped_ms, kStopBoundMs);
  std::vector<std::pair<double, double>> said;
  for (const ReceivedCmdVel& c : confirmed.samples()) said.emplace_back(c.linear.x, c.angular.z);
  ASSERT_GE(said.size(), 3u) << "cmd_vel_confirmed: forward, left, stopped";
  EXPECT_NEAR(said[0].first, 0.1, kLinearStepMps);
  EXPECT_NEAR(said[1].second, 0.5, 0.02);
  EXPECT_EQ(said.back(), std::make_pair(0.0, 0.0)) << "the last velocity confirmed is the stop";
}

TEST_F(BridgeE2E, AFastDdsPublisherKilledWithMinus9MidDriveStopsTheRobot) {
  // Set up by clients/ros_bridge/ros/localhost.sh, as the README has a ROS 2 node
  // (FASTRTPS_DEFAULT_PROFILES_FILE, from the runner's environment).
  ChildProcess publisher({FASTDDS_TWIST_PUBLISHER, "--domain", std::to_string(system_.domain), "--topic",
                          "robot1/cmd_vel", "--linear-mps", "0.05", "--angular-radps", "-0.3", "--rate-hz", "10",
                          "--duration-s", "60"});
  const auto started = Clock::now();
  const auto moving = robots_[0]->first_after(
      started, [](auto& v) { return at_velocity(v, 0.05, -0.3); }, 15000ms);
  ASSERT_TRUE(moving) << "the Fast DDS publisher's velocity never reached robot1's cmd_vel";
  std::this_thread::sleep_for(1s);
  const auto killed_at = Clock::now();
  publisher.kill9();
  const double stopped_ms = stop_ms(0, killed_at);
  std::printf("Fast DDS publisher killed -9 -> stopped: %.0f ms (bound %.0f)\n", stopped_ms, kStopBoundMs);
  EXPECT_LE(stopped_ms, kStopBoundMs);
}

TEST_F(BridgeE2E, StampedBestEffortAtOneKilohertzIsClampedDropsNaNAndHugeSamplesAndCostsTheBridgeLittle) {
  TwistPublisher fast(system_.domain, "robot3/cmd_vel", {.stamped = true, .reliable = false});
  ASSERT_TRUE(fast.wait_for_readers(1, 10s));
  // A sample over 64 KiB (a 200 kB frame_id) never reaches the bridge's reader (CycloneDDS's
  // MaxSampleSize): its velocity is not taken, and the bridge goes on.
  const auto huge_at = Clock::now();
  const std::string huge(200 * 1024, 'x');
  for (int i = 0; i < 15; ++i) {  // 1.5 s at 10 Hz: long enough to drive, were it taken
    fast.publish(0.1, 0, huge);
    std::this_thread::sleep_for(100ms);
  }
  std::this_thread::sleep_for(500ms);
  EXPECT_FALSE(robots_[2]->first_after(
      huge_at, [](auto& v) { return at_velocity(v, 0.1, 0); }, 0ms))
      << "a 200 kB sample drove the robot";
  const pid_t bridge = pid_of(system_, "ros-bridge");
  AirWatch air(DTMFCTL_PATH, system_.server, system_.state_dir + "/air-1khz.jsonl");
  const double cpu_before = cpu_seconds(bridge);
  const auto start = Clock::now();
  const std::int64_t start_unix_ms = unix_ms_now();
  auto next = start;
  // 3 s at 1 kHz, a new velocity each time: 1.0 m/s (beyond a Burger's 0.22) and 0.15 in
  // turn, every 10th a NaN.
  for (int i = 0; i < 3000; ++i) {
    fast.publish(i % 10 == 9 ? std::nan("") : (i % 2 == 0 ? 1.0 : 0.15), 0);
    next += 1ms;
    std::this_thread::sleep_until(next);
  }
  const double elapsed_s = ms_between(start, Clock::now()) / 1000;
  const double cpu_share = (cpu_seconds(bridge) - cpu_before) / elapsed_s;
  const int frames = air.frames_played(start_unix_ms, unix_ms_now(), "robot3");
  // The server sends only the newest velocity, one frame at a time: no more than the air
  // carries back to back (a fast frame is 102.5 ms), whatever the publisher's rate.
  std::printf("1 kHz of changing velocities for %.1f s: %d frames on air for robot3\n", elapsed_s, frames);
  EXPECT_LE(frames, static_cast<int>(elapsed_s * 1000 / 102.5) + 1);
  EXPECT_GT(frames, 0);
  const auto clamped = robots_[2]->first_after(
      start, [](auto& v) { return at_velocity(v, kBurgerMaxLinearMps, 0) || at_velocity(v, 0.15, 0); }, 100ms);
  ASSERT_TRUE(clamped) << "robot3 never drove at its top speed or at 0.15 m/s";
  for (const ReceivedCmdVel& v : robots_[2]->after(start)) {
    ASSERT_FALSE(std::isnan(v.linear.x));
    ASSERT_LE(v.linear.x, kBurgerMaxLinearMps + kLinearStepMps);
  }
  fast.publish(0, 0);
  EXPECT_LT(stop_ms(2, Clock::now()), kStopBoundMs);
  std::printf("1 kHz for %.1f s: the bridge used %.1f %% of a core\n", elapsed_s, 100 * cpu_share);
  EXPECT_LT(cpu_share, 0.25) << "1000 messages a second must cost the bridge little";
  EXPECT_EQ(bridge_log_count(system_, "beyond robot3's limits"), 1) << "clamping is said once";
  EXPECT_EQ(bridge_log_count(system_, "NaN or infinite"), 1) << "a NaN dropped is said once";
}

TEST_F(BridgeE2E, ThreeRobotsThreeTopicsEachMovesOnlyOnItsOwnAndNoneHearsItsOwnOutputBack) {
  TwistPublisher only2(system_.domain, "robot2/cmd_vel", {.stamped = false, .reliable = true});
  ASSERT_TRUE(only2.wait_for_readers(1, 10s));
  // The others idle first: the bridge has closed their streams (the test before drove robot3),
  // so that nothing of theirs is still on the air.
  for (const char* other : {"robot1", "robot3"}) {
    const ReceivedStatus idle = diagnostics_->wait_for(
        other, [](auto& s) { return s.values.count("stream") && s.values.at("stream") == "closed"; }, 5000ms);
    ASSERT_GE(idle.level, 0) << other << "'s stream was not closed within 5 s";
  }
  const auto start = Clock::now();
  const auto released = only2.hold(0.1, 0.2, 2000ms, 100ms);
  ASSERT_TRUE(robots_[1]->first_after(
      start, [](auto& v) { return at_velocity(v, 0.1, 0.2); }, 100ms));
  ASSERT_LT(stop_ms(1, released), kStopBoundMs);
  // Robot2's agent published its velocity on robot2/cmd_vel all along, 20 times a second; had
  // the bridge taken it, robot2 would drive again now. It stays stopped for 3 s.
  const auto after_stop = Clock::now();
  std::this_thread::sleep_for(3s);
  for (const ReceivedCmdVel& v : robots_[1]->after(after_stop)) ASSERT_TRUE(is_stopped(v)) << "robot2 drove again";
  for (int other : {0, 2}) {
    for (const ReceivedCmdVel& v : robots_[other]->after(start)) {
      ASSERT_TRUE(is_stopped(v)) << "robot" << other + 1 << " moved on robot2's topic: " << v.linear.x << " m/s "
                                 << v.angular.z << " rad/s, " << ms_between(start, v.received) << " ms in";
    }
  }
  const ReceivedStatus status = diagnostics_->wait_for(
      "robot2", [](const ReceivedStatus& s) { return s.values.count("robot's own cmd_vel skipped") > 0; }, 3000ms);
  ASSERT_GE(status.level, 0) << "no /diagnostics for robot2";
  const long skipped = std::stol(status.values.at("robot's own cmd_vel skipped"));
  std::printf("robot2's own cmd_vel heard and skipped by the bridge: %ld messages\n", skipped);
  EXPECT_GT(skipped, 20) << "the agent's output did reach the bridge, and was skipped";
}

TEST_F(BridgeE2E, ANav2LikeSquareEndsWhereItsVelocitiesSay) {
  TwistPublisher nav2(system_.domain, "robot2/cmd_vel", {.stamped = false, .reliable = true});
  ASSERT_TRUE(nav2.wait_for_readers(1, 10s));
  const Pose start = pose_of(system_, "robot2");
  // Two sides of a square of 0.3 m and two quarter turns, at 20 Hz, 5 s, then a zero (Nav2
  // at its goal). Integrated: 0.3 m ahead, a quarter turn left, 0.3 m to the left, another.
  constexpr double kSideMps = 0.2, kTurnRadps = 1.5707963;
  const auto start_at = Clock::now();
  nav2.hold(kSideMps, 0, 1500ms, 50ms);
  const auto first = robots_[1]->first_after(
      start_at, [](auto& v) { return at_velocity(v, kSideMps, 0); }, 100ms);
  ASSERT_TRUE(first);
  nav2.hold(0, kTurnRadps, 1000ms, 50ms);
  nav2.hold(kSideMps, 0, 1500ms, 50ms);
  nav2.hold(0, kTurnRadps, 1000ms, 50ms);
  nav2.publish(0, 0);
  ASSERT_LT(stop_ms(1, Clock::now()), kStopBoundMs);
  const double heading = start.heading_deg * M_PI / 180;
  const double want_x = start.x_m + 0.3 * std::cos(heading) - 0.3 * std::sin(heading);
  const double want_y = start.y_m + 0.3 * std::sin(heading) + 0.3 * std::cos(heading);
  const Pose end = pose_of(system_, "robot2");
  const double heading_error = std::remainder(end.heading_deg - (start.heading_deg + 180), 360);
  std::printf(
      "square: first velocity on cmd_vel after %.0f ms; ended at x=%.3f y=%.3f heading %.1f; the velocities "
      "say x=%.3f y=%.3f heading %.1f\n",
      ms_between(start_at, first->received), end.x_m, end.y_m, end.heading_deg, want_x, want_y,
      start.heading_deg + 180);
  // Each change of velocity reaches the robot a frame later, all by about the same delay:
  // what is left is that delay's jitter (tens of ms) over each side, and the ramps. Robot2 has
  // driven before (the test above); a robot's very first frame under its key follows a
  // counter synchronisation, about 0.25 s more, which would shorten the first side by 5 cm.
  EXPECT_LT(std::hypot(end.x_m - want_x, end.y_m - want_y), 0.05);
  EXPECT_LT(std::abs(heading_error), 10);
}

TEST_F(BridgeE2E, DiagnosticsTurnWarnWhenTheRobotsAnswersAreCutAndOkAgainAfter) {
  TwistPublisher keys(system_.domain, "robot3/cmd_vel", {.stamped = false, .reliable = true});
  ASSERT_TRUE(keys.wait_for_readers(1, 10s));
  std::atomic<bool> driving{true};
  // A key now and then, as a user drives: each change is a frame of the stream, which the
  // robot answers (a steady velocity goes out only in joint renewals, which are not answered).
  std::thread publisher([&] {
    for (int i = 0; driving; ++i) {
      keys.publish(i / 5 % 2 == 0 ? 0.05 : 0.04, 0);
      std::this_thread::sleep_for(100ms);
    }
    keys.publish(0, 0);
  });
  auto level_is = [](int level) { return [level](const ReceivedStatus& s) { return s.level == level; }; };
  const ReceivedStatus ok = diagnostics_->wait_for("robot3", level_is(0), 15000ms);
  EXPECT_EQ(ok.level, 0) << "robot3 answering: OK";
  const pid_t agent = pid_of(system_, "agent3");
  ::kill(agent, SIGSTOP);  // the robot hears nothing and answers nothing
  const ReceivedStatus warn = diagnostics_->wait_for(
      "robot3", [](auto& s) { return s.level >= 1; }, 5000ms);
  ::kill(agent, SIGCONT);
  EXPECT_GE(warn.level, 1) << "answers cut, yet /diagnostics stayed OK: " << warn.message;
  std::printf("answers cut: level %d, \"%s\"\n", warn.level, warn.message.c_str());
  const ReceivedStatus again = diagnostics_->wait_for(
      "robot3", [](auto& s) { return s.level == 0 && s.message.starts_with("answering"); }, 20000ms);
  driving = false;
  publisher.join();
  EXPECT_EQ(again.level, 0) << "answers back, yet not OK again";
  std::printf("answers back: level %d, \"%s\"\n", again.level, again.message.c_str());
  EXPECT_LT(stop_ms(2, Clock::now()), kStopBoundMs);
}

TEST_F(BridgeE2E, TheStopForEveryRobotHoldsAgainstAPublisherThatGoesOnUntilItsInputIsZero) {
  TwistPublisher nav2(system_.domain, "robot1/cmd_vel", {.stamped = false, .reliable = true});
  EmptyPublisher stop(system_.domain, "stop_every_robot");
  ASSERT_TRUE(nav2.wait_for_readers(1, 10s));
  ASSERT_TRUE(stop.wait_for_readers(1, 10s));
  const auto start = Clock::now();
  nav2.hold(0.1, 0, 1500ms, 50ms);
  ASSERT_TRUE(robots_[0]->first_after(
      start, [](auto& v) { return at_velocity(v, 0.1, 0); }, 100ms));
  const auto stopped_at = Clock::now();
  stop.publish();
  nav2.hold(0.1, 0, 3000ms, 50ms);  // Nav2 goes on at 20 Hz
  const auto stopped = robots_[0]->first_after(stopped_at, is_stopped, 100ms);
  ASSERT_TRUE(stopped) << "the stop for every robot did not stop robot1";
  std::printf("stop_every_robot -> robot1 stopped: %.0f ms\n", ms_between(stopped_at, stopped->received));
  for (const ReceivedCmdVel& v : robots_[0]->after(stopped->received))
    ASSERT_TRUE(is_stopped(v)) << "driven after a stop";
  // Silent for the timeout: the input is zero, and the next message drives again.
  std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(kTimeoutMs) + 200));
  const auto again = Clock::now();
  const auto released = nav2.hold(0.1, 0, 1500ms, 50ms);
  EXPECT_TRUE(robots_[0]->first_after(
      again, [](auto& v) { return at_velocity(v, 0.1, 0); }, 100ms))
      << "never drove again";
  EXPECT_LT(stop_ms(0, released), kStopBoundMs);
}

}  // namespace
}  // namespace dtmf::test_support
