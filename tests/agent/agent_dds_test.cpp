// dtmf-agent as a separate process driving cmd_vel over real DDS: a subscriber in this
// test (CycloneDDS on loopback, as turtlebot3_node would subscribe) receives TwistStamped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "command/word_codec.h"
#include "dds_test_subscriber.h"
#include "support/run_command.h"

using namespace dtmf;
using test_support::run_command;

namespace {

double stamp_s(const test_support::ReceivedCmdVel& s) { return s.stamp_sec + s.stamp_nanosec * 1e-9; }

class AgentDds : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("CYCLONEDDS_URI", R"(<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>)", 1);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_ = std::filesystem::path(::testing::TempDir()) / ("agent-dds-" + std::to_string(::getpid()));
  const int domain_ = 150 + ::getpid() % 50;
};

}  // namespace

TEST_F(AgentDds, DrivesOverTwistStampedAndStopsWhenTheDurationEnds) {
  ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " encode --wav " + path("x.wav") + " drive --speed 50 --duration 2").exit_code, 0);
  const std::string topic = "cmd_vel_" + std::to_string(::getpid());
  test_support::CmdVelSubscriber subscriber(domain_, "rt/" + topic, true);

  // --realtime: the recording is heard as if live, so the stream is paced like a robot's.
  const auto r = run_command("ROS_DOMAIN_ID=" + std::to_string(domain_) + " " + DTMF_AGENT_PATH + " --audio wav:" +
                             path("x.wav") + " --cmd-vel dds --topic /" + topic + " --db none --realtime --frame-id base_link");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  ASSERT_TRUE(subscriber.wait_for(60, std::chrono::seconds(5))) << subscriber.samples().size() << " samples\n" << r.out;
  const auto samples = subscriber.samples();

  const double period_s = 1.0 / 20;
  const double duration_s = std::get<command::DriveForDuration>(command::quantised(command::DriveForDuration{50, 2})).duration_s;
  int first_move = -1, first_stop = -1;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const auto& s = samples[static_cast<std::size_t>(i)];
    EXPECT_EQ(s.frame_id, "base_link");
    EXPECT_EQ(s.angular.z, 0.0);
    if (s.linear.x != 0) {
      EXPECT_NEAR(s.linear.x, 0.11, 1e-12);
      if (first_move < 0) first_move = i;
    } else if (first_move >= 0 && first_stop < 0) {
      first_stop = i;
    }
    // Steady publishing: stamps one period apart.
    if (i > 0 && i + 1 < static_cast<int>(samples.size())) {
      EXPECT_NEAR(stamp_s(s) - stamp_s(samples[static_cast<std::size_t>(i - 1)]), period_s, 0.002) << i;
    }
  }
  ASSERT_GE(first_move, 0);
  ASSERT_GT(first_stop, first_move);
  const double moved_s = stamp_s(samples[static_cast<std::size_t>(first_stop)]) - stamp_s(samples[static_cast<std::size_t>(first_move)]);
  EXPECT_GE(moved_s, duration_s - period_s);
  EXPECT_LE(moved_s, duration_s + period_s);
  EXPECT_EQ(samples.back().linear.x, 0.0);
  // Stamps are wall-clock times of now, not of some epoch.
  EXPECT_NEAR(stamp_s(samples.back()), std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count(), 30);
}

TEST_F(AgentDds, SigtermPublishesZeroBeforeExiting) {
  // A continuous drive in an endless stream of silence after it: stop it with SIGTERM.
  ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " encode --wav " + path("d.wav") + " drive --speed 100").exit_code, 0);
  ASSERT_EQ(run_command("sox " + path("d.wav") + " " + path("long.wav") + " pad 0 60").exit_code, 0);
  const std::string topic = "cmd_vel_term_" + std::to_string(::getpid());
  test_support::CmdVelSubscriber subscriber(domain_, "rt/" + topic, false);
  const std::string command = "ROS_DOMAIN_ID=" + std::to_string(domain_) + " " + DTMF_AGENT_PATH + " --audio wav:" +
                              path("long.wav") + " --cmd-vel dds --message twist --topic " + topic +
                              " --db none --realtime & pid=$!; sleep 5; kill -TERM $pid; wait $pid";
  const auto r = run_command(command);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("stopping the robot: shutdown signal"), std::string::npos) << r.out;
  ASSERT_TRUE(subscriber.wait_for(10, std::chrono::seconds(2)));
  const auto samples = subscriber.samples();
  bool moved = false;
  for (const auto& s : samples) moved = moved || std::abs(s.linear.x - 0.22) < 1e-9;
  EXPECT_TRUE(moved);
  EXPECT_EQ(samples.back().linear.x, 0.0);
}

TEST_F(AgentDds, ABadDomainFailsBeforeListening) {
  ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " encode --wav " + path("s.wav") + " stop").exit_code, 0);
  const auto r = run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + path("s.wav") + " --cmd-vel dds --db none --ros-domain-id 232 2>&1; ROS_DOMAIN_ID=abc " +
                             DTMF_AGENT_PATH + " --audio wav:" + path("s.wav") + " --cmd-vel dds --db none");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("ROS_DOMAIN_ID"), std::string::npos) << r.out;
}
