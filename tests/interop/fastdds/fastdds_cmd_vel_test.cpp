// Interop: the real dtmf-agent process (CycloneDDS) drives cmd_vel, and an independent
// Fast DDS subscriber (ROS 2 Jazzy's default middleware, types from ROS 2's own message
// definitions: ros2_cmd_vel.idl) receives it, as turtlebot3_node would.
//
// Each test plays a recorded "drive 50 % for 2 s" to the agent in real time and checks on
// the Fast DDS side: the writer discovery announced (type, QoS), that a stricter reader is
// refused, every value, the header stamps, the final zero and how long the motion lasted.
// Run by ctest through in_netns.sh: a private network namespace with multicast on lo, so
// that both sides discover each other with their default settings, on TurtleBot3's ROS
// domain and the real topic name, and nothing leaves the machine.
#include <gtest/gtest.h>
#include <net/if.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "command/word_codec.h"
#include "fastdds_subscriber.h"
#include "support/run_command.h"

using namespace dtmf;
using namespace std::chrono_literals;
using interop::CmdVelMessage;
using interop::CmdVelSample;
using interop::CmdVelState;
using test_support::run_command;

namespace {

constexpr int kDomain = 30;                // TurtleBot3's ROS_DOMAIN_ID
constexpr double kPeriodS = 0.050;         // the agent publishes at 20 Hz
constexpr double kBurgerHalfSpeed = 0.11;  // 50 % of the Burger's 0.22 m/s

double stamp_s(const CmdVelSample& s) { return s.stamp_sec + s.stamp_nanosec * 1e-9; }
double wall_s(std::chrono::system_clock::time_point t) {
  return std::chrono::duration<double>(t.time_since_epoch()).count();
}
bool is_zero(const CmdVelSample& s) {
  return s.linear.x == 0 && s.linear.y == 0 && s.linear.z == 0 && s.angular.x == 0 && s.angular.y == 0 &&
         s.angular.z == 0;
}

// Any interface but lo would let discovery out: ctest runs this through in_netns.sh.
bool only_loopback() {
  struct if_nameindex* names = if_nameindex();
  bool only_lo = names != nullptr;
  for (auto* n = names; n != nullptr && n->if_name != nullptr; ++n)
    only_lo = only_lo && std::string(n->if_name) == "lo";
  if (names != nullptr) if_freenameindex(names);
  return only_lo;
}

struct AgentRun {
  test_support::CommandResult agent;  // exit code and log
  CmdVelState ros;                    // the turtlebot3_node-like reader
  CmdVelState strict;                 // a TRANSIENT_LOCAL reader, which a volatile writer must refuse
};

class FastDdsCmdVel : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(only_loopback()) << "run in a private network namespace: tests/interop/fastdds/in_netns.sh "
                                    "<this binary> (ctest does)";
    std::filesystem::create_directories(dir_);
    ASSERT_EQ(
        run_command(std::string(DTMFCTL_PATH) + " encode --wav " + wav_ + " drive --speed 50 --duration 2").exit_code,
        0);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The agent from start to exit, with both readers listening. Cyclone lets the agent's
  // writer linger until every sample is acknowledged, so when the agent has exited the
  // whole stream is in; the wait only covers the listener thread. (Waiting for the writer
  // to be unmatched would not do: Fast DDS 2.9 does not act on the disposes Cyclone sends
  // for the writer and participant on exit, and drops them when the 10 s lease runs out.)
  AgentRun run_agent(CmdVelMessage message, const std::string& extra_flags) {
    interop::FastDdsCmdVelSubscriber ros(kDomain, "rt/cmd_vel", message);
    interop::FastDdsCmdVelSubscriber strict(kDomain, "rt/cmd_vel", message, interop::ReaderDurability::TransientLocal);
    // No CYCLONEDDS_URI: the agent's DDS as it comes, as on a robot.
    AgentRun run;
    run.agent =
        run_command("env -u CYCLONEDDS_URI ROS_DOMAIN_ID=" + std::to_string(kDomain) + " " + DTMF_AGENT_PATH +
                    " --audio wav:" + wav_ + " --cmd-vel dds --topic /cmd_vel --db none --realtime " + extra_flags);
    ros.wait(
        [](const CmdVelState& s) {
          bool moved = false;
          for (const auto& v : s.samples) moved = moved || !is_zero(v);
          return moved && is_zero(s.samples.back());
        },
        2s);
    run.ros = ros.state();
    run.strict = strict.state();
    return run;
  }

  std::filesystem::path dir_ = std::filesystem::path(::testing::TempDir()) / ("fastdds-" + std::to_string(::getpid()));
  std::string wav_ = (dir_ / "drive.wav").string();
};

// Where the motion starts and stops in the samples (-1: not seen), and how many move.
struct Motion {
  int first_move = -1, first_stop = -1, moving = 0;
};

Motion motion(const std::vector<CmdVelSample>& samples) {
  Motion m;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    if (!is_zero(samples[static_cast<std::size_t>(i)])) {
      ++m.moving;
      if (m.first_move < 0) m.first_move = i;
    } else if (m.first_move >= 0 && m.first_stop < 0) {
      m.first_stop = i;
    }
  }
  return m;
}

// The commanded duration as the agent decodes it (the 6-bit field quantises 2 s).
double commanded_duration_s() {
  return std::get<command::DriveForDuration>(command::quantised(command::DriveForDuration{50, 2})).duration_s;
}

// What both messages share: discovery, QoS, values, the final zero and the motion's length.
void expect_ros2_cmd_vel(const AgentRun& run, const std::string& type) {
  const CmdVelState& s = run.ros;
  // The writers as discovery announced them: ours, reliable, volatile, XCDR1. Cyclone leaves
  // out of its announcement every QoS at the RTPS default for a writer (its trace shows
  // only topic, type and history): Fast DDS reports reliability, durability and
  // representation as those defaults, which is what the agent offers, and would report
  // anything else the agent announced instead.
  // Two writers: the agent's, and its stop guard's (robot_agent/stop_guard.h), which
  // publishes zero if the agent dies. Both must be what a ROS 2 node accepts.
  ASSERT_EQ(s.writers.size(), 2u) << run.agent.out;
  for (const auto& writer : s.writers) {
    EXPECT_EQ(writer.topic, "rt/cmd_vel");
    EXPECT_EQ(writer.type, type);
    EXPECT_EQ(writer.reliability, "RELIABLE");
    EXPECT_EQ(writer.durability, "VOLATILE");
    for (const auto& r : writer.representations) EXPECT_EQ(r, "XCDR");  // none given: XCDR
  }
  // Fast DDS's own matching agrees: our reliable reader matched it with no complaint
  // (a best-effort writer would have been refused), one asking for TRANSIENT_LOCAL was
  // refused for durability.
  EXPECT_GE(s.matched_total, 1);
  EXPECT_EQ(s.incompatible_qos, 0) << s.incompatible_policy;
  EXPECT_EQ(run.strict.matched_total, 0);
  EXPECT_GE(run.strict.incompatible_qos, 1);
  EXPECT_EQ(run.strict.incompatible_policy, "DURABILITY");

  // Speed 50 on a Burger and nothing else; zero before and after. Every payload XCDR1
  // (CDR, either byte order), which a ROS 2 Jazzy node requires.
  ASSERT_FALSE(s.samples.empty()) << run.agent.out;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const CmdVelSample& v = s.samples[i];
    EXPECT_TRUE(v.encapsulation == 0x0000 || v.encapsulation == 0x0001)
        << "sample " << i << ": encapsulation 0x" << std::hex << v.encapsulation;
    const bool half_ahead = std::abs(v.linear.x - kBurgerHalfSpeed) < 1e-12 && v.linear.y == 0 && v.linear.z == 0 &&
                            v.angular.x == 0 && v.angular.y == 0 && v.angular.z == 0;
    EXPECT_TRUE(is_zero(v) || half_ahead)
        << "sample " << i << ": linear " << v.linear.x << " " << v.linear.y << " " << v.linear.z << ", angular "
        << v.angular.x << " " << v.angular.y << " " << v.angular.z;
  }
  const Motion m = motion(s.samples);
  ASSERT_GT(m.first_move, 0) << "no zero seen before the motion, or no motion: " << s.samples.size() << " samples";
  ASSERT_GT(m.first_stop, m.first_move) << "no zero after the motion";
  EXPECT_TRUE(is_zero(s.samples.back()));
  // One sample per period while moving, in one run: the motion's length within a period.
  EXPECT_EQ(m.moving, m.first_stop - m.first_move) << "the motion was interrupted";
  EXPECT_NEAR(m.moving * kPeriodS, commanded_duration_s(), kPeriodS);
}

}  // namespace

TEST_F(FastDdsCmdVel, TwistStampedAsJazzySubscribes) {
  const AgentRun run = run_agent(CmdVelMessage::TwistStamped, "--frame-id base_link");
  ASSERT_EQ(run.agent.exit_code, 0) << run.agent.out;
  expect_ros2_cmd_vel(run, "geometry_msgs::msg::dds_::TwistStamped_");
  if (HasFatalFailure()) return;

  const auto& samples = run.ros.samples;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const CmdVelSample& s = samples[i];
    EXPECT_EQ(s.frame_id, "base_link") << i;
    EXPECT_LT(s.stamp_nanosec, 1'000'000'000u) << i;
    // Wall clock: the publish time. A recording heard in real time (--realtime) is stamped
    // from the audio time of the block being decoded, which runs up to a block ahead of
    // the pacing, so a sample may arrive a few milliseconds "before" its stamp.
    const double lag_s = wall_s(s.received) - stamp_s(s);
    EXPECT_TRUE(lag_s > -0.05 && lag_s < 0.25) << i << ": arrived " << lag_s << " s after its stamp";
    // Steady: one period apart (the final zero, at the end of the recording, comes sooner).
    if (i > 0) {
      const double step = stamp_s(s) - stamp_s(samples[i - 1]);
      if (i + 1 < samples.size())
        EXPECT_NEAR(step, kPeriodS, 0.001) << i;
      else
        EXPECT_TRUE(step > 0 && step <= kPeriodS + 0.001) << step;
    }
  }
  // The motion from its first velocity to its zero, by the stamps.
  const Motion m = motion(samples);
  const double moved_s = stamp_s(samples[static_cast<std::size_t>(m.first_stop)]) -
                         stamp_s(samples[static_cast<std::size_t>(m.first_move)]);
  EXPECT_NEAR(moved_s, commanded_duration_s(), kPeriodS);
}

TEST_F(FastDdsCmdVel, TwistAsHumbleSubscribes) {
  const AgentRun run = run_agent(CmdVelMessage::Twist, "--message twist");
  ASSERT_EQ(run.agent.exit_code, 0) << run.agent.out;
  expect_ros2_cmd_vel(run, "geometry_msgs::msg::dds_::Twist_");
}
