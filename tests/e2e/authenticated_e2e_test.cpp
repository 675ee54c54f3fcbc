// Keys end to end, with the real programs: dtmf-agent and dtmf-server each given a key file
// made by `dtmfctl keygen`, talking through the PulseAudio air with the measured seminar room
// in it both ways (ctest fixtures air and room), the robot's cmd_vel seen by a DDS
// subscriber in this test, both logging to a real PostgreSQL.
//
// - `dtmfctl drive --profile fast` with the same key on both sides is confirmed and moves the
//   robot; with the robot's key changed it is refused, the robot does not move, and the
//   report (SQL, and `dtmfctl report` through GetReport) counts the refusal. The key itself is
//   in no log, no database row and no process's arguments.
// - A keyed server's profile-less Stop, with the seed's ACK played into its microphone, goes
//   authenticated and stops the robot; with the robot gone the played ACK confirms nothing.
// - The sender and the robot are each killed with -9 twenty times while frames are on air.
//   Every MAC input the sender put on air is in its log before the frame sounds (the
//   "on air" lines), and every frame the robot executed in its log: no counter is ever on
//   air for two different frames, and none is executed twice.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "../agent/dds_test_subscriber.h"
#include "../db/temp_database.h"
#include "link/link.h"
#include "physical/wav_file.h"
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

constexpr const char* kSenderAudio = "PULSE_SINK=speaker PULSE_SOURCE=sender_ear.monitor ";
constexpr const char* kRobotAudio = "PULSE_SINK=robot_speaker PULSE_SOURCE=robot_ear.monitor ";

// The secret half of a key file ("key <64 hex digits>").
std::string secret_of(const fs::path& key_file) {
  std::smatch m;
  const std::string text = read_file(key_file);
  return std::regex_search(text, m, std::regex("\nkey ([0-9a-f]{64})")) ? m[1].str() : std::string();
}

class AuthenticatedE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("CYCLONEDDS_URI", R"(<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>)", 1);
    fs::create_directories(dir_);
    subscriber_ = std::make_unique<test_support::CmdVelSubscriber>(domain_, "rt/" + topic_, true);
    for (const char* name : {"robot.key", "other.key"}) {
      const auto made = run_command(std::string(DTMFCTL_PATH) + " keygen " + path(name));
      ASSERT_EQ(made.exit_code, 0) << made.out;
    }
    port_ = test_support::free_port();
  }
  void TearDown() override {
    test_support::stop_process(server_);
    test_support::stop_process(agent_);
    if (HasFailure()) {
      std::printf("%s\n", run_command("tail -n 20 " + path("agent-*.log") + " " + path("server-*.log")).out.c_str());
    }
    fs::remove_all(dir_);
  }

  // Each life of a program logs to its own file: agent-1.log, agent-2.log, ... The first
  // start with each key pairs it (--new-key: the robot refuses a key it has no state for);
  // every later start finds the key's state and must not say so again.
  void start_agent(const std::string& key) {
    const std::string new_key = paired_.insert(key).second ? " --new-key" : "";
    agent_ = test_support::start_process(std::string(kRobotAudio) + "ROS_DOMAIN_ID=" + std::to_string(domain_) + " " +
                                             DTMF_AGENT_PATH + " --key " + path(key) + new_key + " --state-dir " +
                                             path("agent-state") +
                                             " --audio default --ack-out default --cmd-vel sim,dds --topic /" + topic_ +
                                             " --db " + db_.url() + " --spill-file " + path("agent.spill"),
                                         path("agent-" + std::to_string(++agent_lives_) + ".log"));
    const std::string log = path("agent-" + std::to_string(agent_lives_) + ".log");
    ASSERT_TRUE(wait_until([&] { return read_file(log).find("listening to") != std::string::npos; }, 10s))
        << "the robot never listened\n"
        << read_file(log);
  }
  void start_server() {
    server_ = test_support::start_process(std::string(kSenderAudio) + "DTMF_SERVER_KEY_FILE=" + path("robot.key") +
                                              " " + DTMF_SERVER_PATH + " --state-dir " + path("server-state") +
                                              " --port " + std::to_string(port_) + " --db " + db_.url() +
                                              " --spill-file " + path("server.spill"),
                                          path("server-" + std::to_string(++server_lives_) + ".log"));
    ASSERT_TRUE(test_support::wait_healthy(DTMFCTL_PATH, port_)) << read_file(server_log(server_lives_));
  }
  // Both programs up with the same key, then the system ready: the robot confirms a Stop
  // (authenticated, the keyed server's default profile) through the room.
  void start_system() {
    ASSERT_NO_FATAL_FAILURE(start_agent("robot.key"));
    ASSERT_NO_FATAL_FAILURE(start_server());
    ASSERT_TRUE(test_support::wait_robot_answers(DTMFCTL_PATH, port_)) << "the robot never confirmed a Stop";
  }
  // `dtmfctl --json drive --profile fast`: its exit code (0 confirmed, 3 not) and output.
  test_support::CommandResult drive(double speed) {
    return run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                       " --json drive --profile fast --speed " + std::to_string(speed) + " --duration 1 < /dev/null");
  }
  // The same in the background, killed by the caller's schedule: its shell's pid.
  int drive_in_background() {
    return test_support::start_process(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                                           " drive --profile fast --speed 30 --duration 1 < /dev/null",
                                       path("drive.log"));
  }
  // Every log of every life of `program` ("agent", "server"), in order.
  std::vector<std::string> logs(const std::string& program, int lives) const {
    std::vector<std::string> out;
    for (int i = 1; i <= lives; ++i) out.push_back(read_file(path(program + "-" + std::to_string(i) + ".log")));
    return out;
  }
  long moving_messages() {
    long n = 0;
    for (const auto& m : subscriber_->samples()) n += (m.linear.x != 0 || m.angular.z != 0) ? 1 : 0;
    return n;
  }
  // The robot's newest cmd_vel is zero.
  bool standing() {
    const auto samples = subscriber_->samples();
    return !samples.empty() && samples.back().linear.x == 0 && samples.back().angular.z == 0;
  }
  std::string server_log(int life) const { return path("server-" + std::to_string(life) + ".log"); }
  // The drives (`drive_in_background`) with a frame on air in the log of the sender's `life`,
  // by command id.
  std::set<std::string> drives_on_air(int life) const {
    const std::regex on_air(R"(drive_for_duration [^\n]*\(command ([0-9a-f-]+), frame \d+\): on air: )");
    const std::string log = read_file(server_log(life));
    std::set<std::string> ids;
    for (auto it = std::sregex_iterator(log.begin(), log.end(), on_air); it != std::sregex_iterator(); ++it) {
      ids.insert((*it)[1].str());
    }
    return ids;
  }
  // Starts a drive in the background (its pid in `driver`); returns once a frame of it is on air.
  void drive_on_air(int& driver) {
    const std::size_t before = drives_on_air(server_lives_).size();
    driver = drive_in_background();
    ASSERT_TRUE(wait_until([&] { return drives_on_air(server_lives_).size() > before; }, 10s))
        << "no frame of the drive went on air\n"
        << read_file(path("drive.log"));
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  const fs::path dir_ = fs::path(::testing::TempDir()) / ("auth-e2e-" + std::to_string(::getpid()));
  const int domain_ = 100 + ::getpid() % 100;
  const std::string topic_ = "cmd_vel_auth_" + std::to_string(::getpid());
  test_support::TempDatabase db_;
  std::unique_ptr<test_support::CmdVelSubscriber> subscriber_;
  int agent_ = 0, server_ = 0, port_ = 0, agent_lives_ = 0, server_lives_ = 0;
  std::set<std::string> paired_;  // keys the agent was started with
};

}  // namespace

TEST_F(AuthenticatedE2E, KeysOnBothSidesDriveAndAChangedRobotKeyIsRefusedCountedAndStill) {
  ASSERT_NO_FATAL_FAILURE(start_system());
  const auto driven = drive(40);
  ASSERT_EQ(driven.exit_code, 0) << "confirmed with the same key on both sides\n" << driven.out;
  // Progress events say the frames were authenticated.
  EXPECT_NE(driven.out.find("\"authenticated\":true"), std::string::npos) << driven.out;
  EXPECT_EQ(driven.out.find("\"authenticated\":false"), std::string::npos) << driven.out;
  EXPECT_TRUE(wait_until([&] { return moving_messages() > 0; }, 5s)) << "the robot drove";
  EXPECT_NE(read_file(path("agent-1.log")).find("authenticated"), std::string::npos);

  // The robot gets another key: the sender's frames are refused, and nothing moves.
  test_support::stop_process(agent_);
  ASSERT_NO_FATAL_FAILURE(start_agent("other.key"));
  ASSERT_TRUE(wait_until([&] { return standing(); }, 5s)) << "the robot stands before the refused drive";
  const long moving_before = moving_messages();
  const std::string run_id = db_.query<std::string>(
      "INSERT INTO test_runs (id, label, profile, started_at, revision) "
      "VALUES (gen_random_uuid(), 'changed key', 'fast', now(), 1) RETURNING id::text");
  EXPECT_EQ(drive(40).exit_code, 3) << "not confirmed";
  // Kept: a second and a half after the refused drive in which the robot must not move.
  std::this_thread::sleep_for(1500ms);
  EXPECT_EQ(moving_messages(), moving_before) << "the robot did not move";
  db_.query<std::string>("UPDATE test_runs SET ended_at = now() RETURNING id::text");
  EXPECT_TRUE(wait_until([&] { return db_.query<long>("SELECT count(*) FROM receptions WHERE event = 'refused'") > 0; },
                         10s, 100ms))
      << "no refusal reached the database";
  EXPECT_GE(db_.query<long>("SELECT refused_authentication FROM run_report('" + run_id + "'::uuid)"), 1);
  const auto report = run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                                  " report --json " + run_id);
  ASSERT_EQ(report.exit_code, 0) << report.out;
  const auto json = nlohmann::json::parse(report.out, nullptr, false);
  ASSERT_FALSE(json.is_discarded()) << report.out;
  EXPECT_GE(json.value("refused_authentication", 0), 1) << report.out;
  EXPECT_NE(read_file(path("agent-2.log")).find("refused (authentication)"), std::string::npos);

  // The keys: in no log, no row, no command line.
  for (const char* key : {"robot.key", "other.key"}) {
    const std::string secret = secret_of(path(key));
    ASSERT_EQ(secret.size(), 64u);
    for (const char* log : {"agent-1.log", "agent-2.log", "server-1.log"}) {
      EXPECT_EQ(read_file(path(log)).find(secret), std::string::npos) << key << " in " << log;
    }
    EXPECT_EQ(db_.query<long>("SELECT count(*) FROM (SELECT row_to_json(t)::text AS j FROM receptions t UNION ALL "
                              "SELECT row_to_json(t)::text FROM frame_attempts t UNION ALL SELECT "
                              "row_to_json(t)::text FROM commands t) rows WHERE j LIKE '%" +
                              secret + "%'"),
              0);
    for (const int pid : {agent_, server_}) {
      EXPECT_EQ(read_file("/proc/" + std::to_string(pid) + "/cmdline").find(secret), std::string::npos);
      EXPECT_EQ(read_file("/proc/" + std::to_string(pid) + "/environ").find(secret), std::string::npos);
    }
  }
}

TEST_F(AuthenticatedE2E, SenderAndRobotKilledTwentyTimesEachNeverUseACounterTwice) {
  ASSERT_NO_FATAL_FAILURE(start_agent("robot.key"));
  ASSERT_NO_FATAL_FAILURE(start_server());
  // Kills at moments spread over a drive's frames, counted from its first frame on air: its
  // synchronisation, its command, their answers and retransmissions. The moment is what the
  // test varies: kept sleeps.
  const auto kill_moment = [](int life) { return std::chrono::milliseconds(40 + (life * 53) % 420); };
  for (int life = 0; life < 20; ++life) {
    int driver = 0;
    ASSERT_NO_FATAL_FAILURE(drive_on_air(driver)) << "sender life " << server_lives_;
    std::this_thread::sleep_for(kill_moment(life));
    test_support::stop_process(server_, SIGKILL);
    test_support::stop_process(driver);
    ASSERT_NO_FATAL_FAILURE(start_server());
  }
  for (int life = 0; life < 20; ++life) {
    int driver = 0;
    ASSERT_NO_FATAL_FAILURE(drive_on_air(driver)) << "robot life " << agent_lives_;
    std::this_thread::sleep_for(kill_moment(life) + 100ms);  // 100 ms more: the robot hears a frame's end
    test_support::stop_process(agent_, SIGKILL);
    test_support::stop_process(driver);
    ASSERT_NO_FATAL_FAILURE(start_agent("robot.key"));
  }
  EXPECT_EQ(drive(20).exit_code, 0) << "both sides recovered";

  // The sender: each counter on air for one frame only (a retransmission of a frame within
  // one command is the same frame: the same line but for its attempt).
  const std::regex on_air(
      R"(\(command ([0-9a-f-]+), frame (\d+)\): on air: (\w+) frame, key (\w+), robot (\d+), counter (\d+), attempt)");
  std::map<std::uint64_t, std::set<std::string>> frames_of_counter;
  for (const std::string& log : logs("server", server_lives_)) {
    for (auto it = std::sregex_iterator(log.begin(), log.end(), on_air); it != std::sregex_iterator(); ++it) {
      const auto& m = *it;
      frames_of_counter[std::stoull(m[6].str())].insert(m[1].str() + " frame " + m[2].str() + " " + m[3].str() +
                                                        " key " + m[4].str() + " robot " + m[5].str());
    }
  }
  // Every life killed had put its drive on air (the loops waited for that before each kill):
  // each of the sender's first twenty lives one drive, its last life the robot's twenty and
  // the last one.
  for (int life = 1; life <= 20; ++life) EXPECT_EQ(drives_on_air(life).size(), 1u) << "sender life " << life;
  EXPECT_EQ(drives_on_air(server_lives_).size(), 21u) << "the sender's last life";
  for (const auto& [counter, frames] : frames_of_counter) {
    EXPECT_EQ(frames.size(), 1u) << "counter " << counter << " went on air for " << frames.size() << " frames";
  }
  // The robot: each counter executed once, and in increasing order across its lives.
  const std::regex executed(R"(counter (\d+) authenticated: ACK \(command\))");
  std::vector<std::uint64_t> counters;
  for (const std::string& log : logs("agent", agent_lives_)) {
    for (auto it = std::sregex_iterator(log.begin(), log.end(), executed); it != std::sregex_iterator(); ++it) {
      counters.push_back(std::stoull((*it)[1].str()));
    }
  }
  std::printf("counters on air: %zu, executed: %zu (sender lives %d, robot lives %d)\n", frames_of_counter.size(),
              counters.size(), server_lives_, agent_lives_);
  EXPECT_GE(counters.size(), 10u);
  for (std::size_t i = 1; i < counters.size(); ++i) {
    EXPECT_GT(counters[i], counters[i - 1]) << "executed counter " << counters[i] << " after " << counters[i - 1];
  }
}

// The operator's Stop from a keyed server given no profile, while a stranger's phone plays the
// seed profile's ACK (its fixed 2.5 + 3.5 kHz chord) into the sender's microphone: the Stop
// goes authenticated, the keyed robot stops, and the tag of the robot's own ACK confirms it.
// With the robot gone, nothing but the forger answers, and no Stop is confirmed. (Before issue
// 34 the Stop went out as a seed frame: the robot refused it and drove on, and the played ACK
// made `dtmfctl stop` print "confirmed" and exit 0.)
TEST_F(AuthenticatedE2E, AProfileLessStopStopsTheKeyedRobotAndAPlayedSeedAckConfirmsNothing) {
  ASSERT_NO_FATAL_FAILURE(start_system());
  // Driving on, with no end and no profile: the server's default, authenticated with a key.
  const auto driving = run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                                   " --json drive --speed 40 < /dev/null");
  ASSERT_EQ(driving.exit_code, 0) << driving.out;
  EXPECT_EQ(driving.out.find("\"authenticated\":false"), std::string::npos) << driving.out;
  ASSERT_TRUE(wait_until([&] { return moving_messages() > 0; }, 5s)) << "the keyed robot drives";

  // The forger: 60 s of the seed's ACK, one after another, into the sender's microphone.
  const auto seed = link::make_link(seed_profile());
  link::Reception accepted;
  accepted.intact = true;
  accepted.event = link::ReceptionEvent::Command;
  const std::vector<float> ack = seed->answer_audio(accepted);
  std::vector<float> forged;
  while (forged.size() < static_cast<std::size_t>(60 * seed_profile().sample_rate_hz)) {
    forged.insert(forged.end(), ack.begin(), ack.end());
    forged.resize(forged.size() + static_cast<std::size_t>(seed_profile().samples_for_ms(20)), 0.0f);
  }
  physical::write_wav_file(path("seed-ack.wav"), forged, seed_profile().sample_rate_hz);
  const int forger =
      test_support::start_process("PULSE_SINK=sender_ear exec paplay " + path("seed-ack.wav"), path("forger.log"));

  const auto stop = [&] {
    return run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                       " --json stop < /dev/null");
  };
  const auto stopped = stop();
  EXPECT_EQ(stopped.exit_code, 0) << stopped.out;
  EXPECT_NE(stopped.out.find("\"event\":\"confirmed\""), std::string::npos) << stopped.out;
  EXPECT_NE(stopped.out.find("\"answer_authenticated\":true"), std::string::npos) << stopped.out;
  EXPECT_EQ(stopped.out.find("\"answer_authenticated\":false"), std::string::npos) << stopped.out;
  EXPECT_EQ(stopped.out.find("\"profile\":\"seed\""), std::string::npos) << stopped.out;
  // The robot stands: its last cmd_vel is zero, and nothing moves from here on.
  EXPECT_TRUE(wait_until([&] { return standing(); }, 2s)) << "the keyed robot stopped";
  const long moving_after_stop = moving_messages();
  std::this_thread::sleep_for(1000ms);  // kept: a second in which it must not move again
  EXPECT_EQ(moving_messages(), moving_after_stop) << "the keyed robot stayed stopped";

  // Without the robot only the forger answers: no confirmation, whatever the profile asked.
  test_support::stop_process(agent_);
  agent_ = 0;
  const auto unanswered = stop();
  EXPECT_EQ(unanswered.exit_code, 3) << unanswered.out;
  EXPECT_EQ(unanswered.out.find("\"event\":\"confirmed\""), std::string::npos) << unanswered.out;
  EXPECT_EQ(unanswered.out.find("\"event\":\"ack\""), std::string::npos) << unanswered.out;
  EXPECT_TRUE(test_support::process_running(forger))
      << "the forger played all along: " << read_file(path("forger.log"));
  test_support::stop_process(forger);
}
