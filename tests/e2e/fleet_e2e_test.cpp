// A room of robots with the real programs: three dtmf-agent processes at addresses 1-3, each
// with its own key and the room key, in one measured room inside the PulseAudio air
// (tests/e2e/fleet_fixture.sh: every loudspeaker into every microphone), one dtmf-server
// driving them by name (--robots, --room-key), and each robot's cmd_vel seen by a DDS
// subscriber on its own topic (/robot<k>/cmd_vel), as `scripts/quickstart --robots 3` runs them.
//
// - A command to robot2 moves robot2 only.
// - `dtmfctl stop --all` stops all three, each driving at once before it.
// - Robot 2's frames, recorded off the air and played again into the room, move no robot:
//   robot2 has taken newer counters, and the others are not at address 2.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "../agent/dds_test_subscriber.h"
#include "../db/temp_database.h"
#include "support/free_port.h"
#include "support/processes.h"
#include "support/read_file.h"
#include "support/wait_for.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::read_file;
using test_support::run_command;
using test_support::wait_until;
namespace fs = std::filesystem;

namespace {

constexpr int kRobots = 3;

class FleetE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("CYCLONEDDS_URI", R"(<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>)", 1);
    fs::create_directories(dir_);
    const auto room = run_command(fixture_ + " start " + DTMF_AIR_DIR + " " + DTMF_ROOM_PATH + " " + DTMF_E2E_RIR +
                                  " " + std::to_string(kRobots) + " 2>&1");
    ASSERT_EQ(room.exit_code, 0) << room.out;
    std::string roster = "[";
    for (int k = 1; k <= kRobots; ++k) {
      const std::string name = "robot" + std::to_string(k);
      ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " keygen " + path(name + ".key")).exit_code, 0);
      roster += std::string(k > 1 ? ", " : "") + "{\"name\": \"" + name + "\", \"address\": " + std::to_string(k) +
                ", \"key\": \"" + path(name + ".key") + "\"}";
      subscribers_[k - 1] =
          std::make_unique<test_support::CmdVelSubscriber>(domain_, "rt/" + topic_prefix_ + name + "/cmd_vel", true);
    }
    ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " keygen " + path("room.key")).exit_code, 0);
    std::ofstream(path("robots.json")) << roster << "]\n";
    port_ = test_support::free_port();
    for (int k = 1; k <= kRobots; ++k) {
      const std::string name = "robot" + std::to_string(k);
      agents_[k - 1] = test_support::start_process(
          "PULSE_SINK=room_air PULSE_SOURCE=" + name + "_ear.monitor ROS_DOMAIN_ID=" + std::to_string(domain_) + " " +
              DTMF_AGENT_PATH + " --address " + std::to_string(k) + " --host " + name + " --key " +
              path(name + ".key") + " --room-key " + path("room.key") + " --new-key --state-dir " +
              path(name + "-state") + " --audio default --ack-out default --cmd-vel sim,dds --topic /" + topic_prefix_ +
              name + "/cmd_vel --db " + db_.url() + " --spill-file " + path(name + ".spill"),
          path(name + ".log"));
    }
    for (int k = 1; k <= kRobots; ++k) {
      const std::string log = path("robot" + std::to_string(k) + ".log");
      ASSERT_TRUE(wait_until([&] { return read_file(log).find("listening to") != std::string::npos; }, 15s))
          << read_file(log);
    }
    server_ = test_support::start_process(
        "PULSE_SINK=room_air PULSE_SOURCE=fleet_sender_ear.monitor " + std::string(DTMF_SERVER_PATH) + " --robots " +
            path("robots.json") + " --room-key " + path("room.key") + " --state-dir " + path("server-state") +
            " --host sender-a --port " + std::to_string(port_) + " --db " + db_.url() + " --spill-file " +
            path("server.spill"),
        path("server.log"));
    ASSERT_TRUE(test_support::wait_healthy(DTMFCTL_PATH, port_)) << read_file(path("server.log"));
    // Ready: each robot confirms a Stop of its own through the room.
    for (int k = 1; k <= kRobots; ++k) {
      ASSERT_TRUE(wait_until([&] { return ctl(k, "stop").exit_code == 0; }, 60s, 100ms))
          << "robot" << k << " never confirmed a Stop\n"
          << read_file(path("robot" + std::to_string(k) + ".log"));
    }
  }
  void TearDown() override {
    test_support::stop_process(server_);
    for (const int agent : agents_) test_support::stop_process(agent);
    if (recorder_) test_support::stop_process(recorder_);
    if (HasFailure()) {
      std::printf("%s\n", run_command("tail -n 15 " + path("*.log")).out.c_str());
    }
    run_command(fixture_ + " stop " + DTMF_AIR_DIR);
    fs::remove_all(dir_);
  }

  // `dtmfctl [--robot robot<k>] ARGS` (k 0: no robot named).
  test_support::CommandResult ctl(int k, const std::string& args) {
    return run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                       (k > 0 ? " --robot robot" + std::to_string(k) : "") + " " + args + " < /dev/null 2>&1");
  }
  bool moved(int k) const {
    for (const auto& m : subscribers_[k - 1]->samples()) {
      if (m.linear.x != 0 || m.angular.z != 0) return true;
    }
    return false;
  }
  std::size_t moving_samples(int k) const {
    std::size_t n = 0;
    for (const auto& m : subscribers_[k - 1]->samples()) n += (m.linear.x != 0 || m.angular.z != 0) ? 1 : 0;
    return n;
  }
  bool standing(int k) const {
    const auto samples = subscribers_[k - 1]->samples();
    return !samples.empty() && samples.back().linear.x == 0 && samples.back().angular.z == 0;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  const fs::path dir_ = fs::path(::testing::TempDir()) / ("fleet-e2e-" + std::to_string(::getpid()));
  const std::string fixture_ = std::string(DTMF_SOURCE_DIR) + "/tests/e2e/fleet_fixture.sh";
  const int domain_ = 100 + ::getpid() % 100;
  const std::string topic_prefix_ = "fleet" + std::to_string(::getpid()) + "_";
  test_support::TempDatabase db_;
  std::array<std::unique_ptr<test_support::CmdVelSubscriber>, kRobots> subscribers_;
  std::array<int, kRobots> agents_{};
  int server_ = 0, port_ = 0, recorder_ = 0;
};

}  // namespace

TEST_F(FleetE2E, ACommandMovesOnlyItsRobotAStopForEveryRobotStopsAllAndAReplayMovesNone) {
  // A command to robot2: robot2 alone moves. The air is recorded meanwhile, for the replay.
  recorder_ = test_support::start_process(
      "parec -d room_air.monitor --file-format=wav --rate=48000 --channels=1 " + path("robot2.wav"), path("parec.log"));
  const auto to_robot2 = ctl(2, "drive --speed 40 --duration 1");
  test_support::stop_process(recorder_, SIGINT);
  recorder_ = 0;
  ASSERT_EQ(to_robot2.exit_code, 0) << to_robot2.out;
  ASSERT_TRUE(wait_until([&] { return moved(2); }, 5s)) << "robot2 did not move";
  std::this_thread::sleep_for(1500ms);  // robot2's drive ends; robot1 and robot3 heard its frame
  EXPECT_FALSE(moved(1)) << "robot1 executed robot2's frame";
  EXPECT_FALSE(moved(3)) << "robot3 executed robot2's frame";

  // Robot 2's frames, played again into the room after a newer one: nobody moves.
  ASSERT_EQ(ctl(2, "stop").exit_code, 0);
  ASSERT_TRUE(wait_until([&] { return standing(2); }, 5s));
  const std::array<std::size_t, kRobots> before{moving_samples(1), moving_samples(2), moving_samples(3)};
  const auto replay = run_command("PULSE_SINK=room_air paplay " + path("robot2.wav") + " 2>&1");
  ASSERT_EQ(replay.exit_code, 0) << replay.out;
  std::this_thread::sleep_for(1500ms);
  for (int k = 1; k <= kRobots; ++k) EXPECT_EQ(moving_samples(k), before[k - 1]) << "robot" << k << " moved";
  EXPECT_TRUE(wait_until(
      [&] {
        return db_.query<long>(
                   "SELECT count(*) FROM receptions WHERE host = 'robot2' AND event = 'refused' "
                   "AND reason = 'authentication'") > 0;
      },
      10s, 100ms))
      << "robot2 did not log the replayed frame as refused";

  // All three drive; one stop for every robot stops them all.
  for (int k = 1; k <= kRobots; ++k) ASSERT_EQ(ctl(k, "drive --speed 30").exit_code, 0) << "robot" << k;
  for (int k = 1; k <= kRobots; ++k) ASSERT_TRUE(wait_until([&] { return !standing(k); }, 5s)) << "robot" << k;
  const auto stop_all = ctl(0, "--json stop --all");
  ASSERT_EQ(stop_all.exit_code, 0) << stop_all.out;
  EXPECT_NE(stop_all.out.find("\"event\":\"sent\""), std::string::npos) << stop_all.out;
  for (int k = 1; k <= kRobots; ++k) {
    EXPECT_TRUE(wait_until([&] { return standing(k); }, 2s)) << "robot" << k << " still drives";
    EXPECT_NE(read_file(path("robot" + std::to_string(k) + ".log")).find("stop every_robot"), std::string::npos)
        << "robot" << k << " did not log the stop for every robot";
  }
  // The database names each robot: its commands by name, its receptions by address.
  EXPECT_TRUE(wait_until(
      [&] {
        return db_.query<long>("SELECT count(DISTINCT robot) FROM commands WHERE host = 'sender-a'") == kRobots &&
               db_.query<long>("SELECT count(*) FROM commands WHERE every_robot AND outcome = 'sent'") == 1;
      },
      10s, 100ms));
  EXPECT_EQ(db_.query<long>("SELECT count(DISTINCT robot_address) FROM receptions WHERE command = 'stop every_robot'"),
            kRobots);
}
