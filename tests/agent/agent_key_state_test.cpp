// dtmf-agent with a key, offline, and its counter state (issue 34): a recording made under
// the key (`dtmfctl encode --key`: a synchronisation frame and a command) is executed only by
// a robot paired with --new-key. A wiped state directory, or a state file that is empty or
// garbled, stops the agent at start with what to do, and nothing is executed; --new-key for a
// key used here is refused; the robot's lock is held before it listens, so a second agent on
// the same state directory fails at start; a state directory others may write is refused.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "physical/wav_file.h"
#include "support/processes.h"
#include "support/run_command.h"
#include "support/wait_for.h"

using namespace dtmf;
using test_support::json_lines;
using test_support::run_command;
namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class AgentKeyState : public ::testing::Test {
 protected:
  fs::path dir_ = fs::path(::testing::TempDir()) / ("agent-key-" + std::to_string(::getpid()));
  void SetUp() override {
    fs::create_directories(dir_);
    ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " keygen " + path("robot.key")).exit_code, 0);
    std::smatch m;
    const std::string text = read_file(path("robot.key"));
    ASSERT_TRUE(std::regex_search(text, m, std::regex("\nkey-id ([0-9a-f]{8})"))) << text;
    key_id_ = m[1];
    // The old recording: made earlier under the key, by a sender with its own state.
    const auto made = run_command(std::string(DTMFCTL_PATH) + " encode --key " + path("robot.key") + " --state-dir " +
                                  path("sender-state") + " --profile fast --json --wav " + path("old.wav") +
                                  " drive --speed 40 --duration 1");
    ASSERT_EQ(made.exit_code, 0) << made.out;
    ASSERT_EQ(json_lines(made.out).size(), 2u) << "a synchronisation frame, then the command";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string robot_file() const { return path("robot-state/robot-" + key_id_); }

  // dtmf-agent with the key on `wav`: its exit code, and stdout (cmd_vel as JSON lines) and
  // stderr (the log) together.
  test_support::CommandResult agent(const std::string& wav, const std::string& extra = "") {
    return run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + wav + " --cmd-vel log --db none --key " +
                       path("robot.key") + " --state-dir " + path("robot-state") + " " + extra);
  }
  static bool moved(const std::string& out) {
    for (const auto& line : json_lines(out)) {
      if (line["linear_mps"].get<double>() != 0 || line["angular_radps"].get<double>() != 0) return true;
    }
    return false;
  }
  // Nothing was executed, nor even heard: the agent stopped before it listened.
  static void expect_nothing_executed(const test_support::CommandResult& r, const std::string& what) {
    EXPECT_EQ(r.exit_code, 1) << what << ": " << r.out;
    EXPECT_FALSE(moved(r.out)) << what << ": " << r.out;
    EXPECT_EQ(r.out.find("ACK ("), std::string::npos) << what << ": " << r.out;
    EXPECT_EQ(r.out.find("listening to"), std::string::npos) << what << ": " << r.out;
  }

  std::string key_id_;
};

}  // namespace

TEST_F(AgentKeyState, AWipedStateDirectoryStopsTheAgentAndNewKeyPairsIt) {
  // The state directory wiped (never made, here): the old recording must not run.
  auto r = agent(path("old.wav"));
  expect_nothing_executed(r, "wiped");
  EXPECT_NE(r.out.find("no counter state for key " + key_id_ + " in " + path("robot-state")), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("if this key was just made, start once with --new-key"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("make a new key (dtmfctl keygen)"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(robot_file()));

  // Paired: the key is new here, and says so once.
  r = agent(path("old.wav"), "--new-key");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(moved(r.out)) << r.out;
  EXPECT_NE(r.out.find("authenticated: ACK (command)"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_match(read_file(robot_file()), std::regex("accepted [1-9][0-9]*\n")))
      << read_file(robot_file());
  const std::string state = read_file(robot_file());

  // Restarted as usual (no --new-key): the same recording is old now.
  r = agent(path("old.wav"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_FALSE(moved(r.out)) << r.out;
  EXPECT_NE(r.out.find("refused (authentication)"), std::string::npos) << r.out;
  // --new-key again, by the flag or its environment variable: refused, the state kept.
  for (const std::string& how : {std::string("--new-key"), std::string("")}) {
    r = how.empty() ? run_command("DTMF_AGENT_NEW_KEY=true " + std::string(DTMF_AGENT_PATH) +
                                  " --audio wav:" + path("old.wav") + " --cmd-vel log --db none --key " +
                                  path("robot.key") + " --state-dir " + path("robot-state"))
                    : agent(path("old.wav"), how);
    expect_nothing_executed(r, "--new-key again");
    EXPECT_NE(r.out.find("key " + key_id_ + " has been used here (last accepted "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("drop --new-key"), std::string::npos) << r.out;
    EXPECT_EQ(read_file(robot_file()), state);
  }
  // --new-key means nothing without a key.
  r = run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + path("old.wav") + " --db none --new-key");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--key"), std::string::npos) << r.out;
}

TEST_F(AgentKeyState, AnEmptyOrGarbledStateFileStopsTheAgent) {
  for (const std::string& text :
       {std::string(""), std::string("accepted"), std::string("accepted x\n"), std::string("accepted 12 junk\n"),
        std::string("garbage\n"), std::string("\x00\xff\x01\x02", 4)}) {
    fs::remove_all(path("robot-state"));
    fs::create_directory(path("robot-state"));
    fs::permissions(path("robot-state"), fs::perms::owner_all);
    std::ofstream(robot_file(), std::ios::binary) << text;
    for (const std::string& extra : {std::string(""), std::string("--new-key")}) {
      const auto r = agent(path("old.wav"), extra);
      const std::string what = ::testing::PrintToString(text) + " " + extra;
      expect_nothing_executed(r, what);
      EXPECT_NE(r.out.find("the counter state " + robot_file() + " is damaged: "), std::string::npos)
          << what << ": " << r.out;
      EXPECT_NE(r.out.find("The robot cannot tell which frames are old. Make a new key (dtmfctl keygen), install it "
                           "on both sides, and start dtmf-agent --new-key"),
                std::string::npos)
          << what << ": " << r.out;
      EXPECT_EQ(read_file(robot_file()), text) << what;
    }
  }
}

// The robot's lock is taken before the agent listens: a second agent on the same state
// directory stops at start, while the first still listens.
TEST_F(AgentKeyState, ASecondAgentOnTheSameStateDirectoryFailsAtStart) {
  // Twenty seconds of silence, heard as if live.
  physical::write_wav_file(path("quiet.wav"), std::vector<float>(48000 * 20, 0.0f), 48000);
  ASSERT_EQ(agent(path("quiet.wav"), "--new-key").exit_code, 0);
  const int first = test_support::start_process(std::string(DTMF_AGENT_PATH) + " --audio wav:" + path("quiet.wav") +
                                                    " --realtime --cmd-vel log --db none --key " + path("robot.key") +
                                                    " --state-dir " + path("robot-state"),
                                                path("first.log"));
  ASSERT_TRUE(test_support::wait_until(
      [&] { return read_file(path("first.log")).find("listening to") != std::string::npos; }, std::chrono::seconds(10)))
      << read_file(path("first.log"));
  const auto second = agent(path("old.wav"));
  EXPECT_TRUE(test_support::process_running(first)) << read_file(path("first.log"));
  test_support::stop_process(first);
  expect_nothing_executed(second, "a second agent");
  EXPECT_NE(
      second.out.find("another process keeps its robot counter in " + path("robot-state") + " for key " + key_id_),
      std::string::npos)
      << second.out;
}

TEST_F(AgentKeyState, AStateDirectoryOthersMayWriteStopsTheAgent) {
  ASSERT_EQ(agent(path("old.wav"), "--new-key").exit_code, 0);
  ASSERT_EQ(::chmod(path("robot-state").c_str(), 0777), 0);
  const auto r = agent(path("old.wav"));
  expect_nothing_executed(r, "mode 0777");
  EXPECT_NE(r.out.find("the state directory " + path("robot-state") + " has mode 0777"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("chmod 700 " + path("robot-state")), std::string::npos) << r.out;
}
