// dtmfctl against a live system of real processes: dtmf-server and dtmf-agent talking
// through the PulseAudio air, logging to PostgreSQL (ctest fixtures air and pg).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "profile/link_profile.h"
#include "support/air_recording.h"
#include "support/free_port.h"
#include "support/processes.h"
#include "support/run_command.h"

using dtmf::test_support::run_command;
using dtmf::test_support::whole_json_lines;
namespace fs = std::filesystem;

namespace {

using dtmf::test_support::free_port;

const fs::path kDir = fs::path(::testing::TempDir()) / ("dtmfctl-live-" + std::to_string(::getpid()));

int start(const std::string& command, const std::string& log) {
  return dtmf::test_support::start_process(command, (kDir / log).string());
}

void wait_healthy(int port) {
  if (!dtmf::test_support::wait_healthy(DTMFCTL_PATH, port)) FAIL() << "server on port " << port << " did not come up";
}

class DtmfctlLive : public ::testing::Test {
 protected:
  // One system for all the tests: the robot, a server that hears it, and a server that
  // hears nothing (its frames go unanswered).
  static void SetUpTestSuite() {
    fs::create_directories(kDir);
    const std::string db = std::getenv("DTMF_DB_URL") ? std::getenv("DTMF_DB_URL") : "none";
    agent_ = start(std::string(DTMF_AGENT_PATH) + " --audio default --ack-out default --cmd-vel sim --db " + db +
                       " --spill-file " + (kDir / "agent.spill").string(),
                   "agent.log");
    port_ = free_port();
    server_ = start(std::string(DTMF_SERVER_PATH) + " --address 127.0.0.1 --port " + std::to_string(port_) + " --db " +
                        db + " --spill-file " + (kDir / "server.spill").string(),
                    "server.log");
    deaf_port_ = free_port();
    deaf_ = start(std::string(DTMF_SERVER_PATH) + " --address 127.0.0.1 --port " + std::to_string(deaf_port_) +
                      " --audio-out wav:" + (kDir / "deaf.wav").string() + " --audio-in none --db none",
                  "deaf.log");
    wait_healthy(port_);
    wait_healthy(deaf_port_);
    // Ready once the robot confirms a Stop through the air (outside any run: no report counts it).
    ASSERT_TRUE(dtmf::test_support::wait_robot_answers(DTMFCTL_PATH, port_)) << "the robot never confirmed a Stop";
  }
  // Every process must be gone before the next test starts its own.
  static void TearDownTestSuite() {
    for (int pid : {agent_, server_, deaf_}) dtmf::test_support::stop_process(pid);
    fs::remove_all(kDir);
  }
  static std::string ctl(const std::string& args, int port = port_) {
    return std::string(DTMFCTL_PATH) + " " + args + " --server 127.0.0.1:" + std::to_string(port);
  }
  static inline int agent_ = 0, server_ = 0, deaf_ = 0, port_ = 0, deaf_port_ = 0;
};

}  // namespace

TEST_F(DtmfctlLive, DriveShowsEveryFrameAndExitsZeroWhenConfirmed) {
  const auto r = run_command(ctl("drive --speed 50 --duration 1") + " < /dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  for (const char* frame : {"frame 1/3", "frame 2/3", "frame 3/3"})
    EXPECT_NE(r.out.find(frame), std::string::npos) << r.out;
  std::size_t acks = 0;
  for (std::size_t at = r.out.find("ACK after"); at != std::string::npos; at = r.out.find("ACK after", at + 1)) ++acks;
  EXPECT_EQ(acks, 3u) << r.out;
  EXPECT_NE(r.out.find("drive_for_duration speed=50.0% duration=1.03s: confirmed"), std::string::npos) << r.out;
}

TEST_F(DtmfctlLive, JsonGivesOneObjectPerEvent) {
  const auto r = run_command(ctl("turn --rotation -40 --duration 1 --json") + " < /dev/null", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::vector<std::string> events;
  for (const auto& line : whole_json_lines(r.out)) {
    events.push_back(line["event"]);
    EXPECT_EQ(line["frame_count"], 3);
    // A queued command has no frames yet: they are numbered as they go on air.
    EXPECT_EQ(line["frame"].get<std::string>().size(), line["event"] == "queued" ? 0u : 16u) << line;
  }
  EXPECT_EQ(events, (std::vector<std::string>{"queued", "transmitting", "ack", "transmitting", "ack", "transmitting",
                                              "ack", "confirmed"}));
}

TEST_F(DtmfctlLive, WithoutATerminalAnUnconfirmedFrameFailsOrContinuesAsTold) {
  auto r = run_command(ctl("reset", deaf_port_) + " < /dev/null");
  EXPECT_EQ(r.exit_code, 3) << r.out;
  EXPECT_NE(r.out.find("not confirmed"), std::string::npos) << r.out;
  r = run_command(ctl("reset --on-unconfirmed continue", deaf_port_) + " < /dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("continued"), std::string::npos) << r.out;
}

TEST_F(DtmfctlLive, OnATerminalThePersonIsAskedContinueRetransmitAbort) {
  // script(1) gives dtmfctl a pseudo-terminal; the answers come through it: retransmit, then continue.
  const auto r =
      run_command("(sleep 4; echo r; sleep 4; echo c) | script -qfec '" + ctl("reset", deaf_port_) + "' /dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  std::size_t asked = 0;
  for (std::size_t at = r.out.find("[c]ontinue / [r]etransmit / [a]bort?"); at != std::string::npos;
       at = r.out.find("[c]ontinue / [r]etransmit / [a]bort?", at + 1))
    ++asked;
  EXPECT_EQ(asked, 2u) << r.out;
  EXPECT_NE(r.out.find("attempt 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reset: continued"), std::string::npos) << r.out;
}

TEST_F(DtmfctlLive, BadValuesAreUsageErrorsAndAMissingServerIsOneLine) {
  auto r = run_command(ctl("drive --speed 120") + " < /dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("speed_percent 120 is out of range"), std::string::npos) << r.out;
  r = run_command(std::string(DTMFCTL_PATH) + " stop --server 127.0.0.1:1 < /dev/null");
  EXPECT_EQ(r.exit_code, 4) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find("cannot reach dtmf-server at 127.0.0.1:1"), std::string::npos) << r.out;
  EXPECT_EQ(run_command(ctl("health")).exit_code, 0);
  // Connection flags before the subcommand, as kubectl and grpcurl users write them.
  r = run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) +
                  " --json runs --limit 1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
}

// A sender kept off the CPU plays its chord with a hole in it: on a CI machine the air split
// seed chords with up to 460 ms of silence, and the rest of one passed as a second chord.
// Here the server is stopped (SIGSTOP) for 460 ms in the middle of the first frame's chord.
// The robot must hear each of the command's three frames once and run the command
// (signal/debouncer.h: a chord resumed after a dropout is the same chord).
TEST_F(DtmfctlLive, AChordWithAHoleInItIsHeardOnce) {
  dtmf::test_support::AirRecording air((kDir / "hole.wav").string());
  const auto agent_log_at = fs::file_size(kDir / "agent.log");
  FILE* ctl_out = ::popen((ctl("drive --speed 50 --duration 1") + " < /dev/null 2>&1").c_str(), "r");
  ASSERT_NE(ctl_out, nullptr);
  std::string out;
  bool paused = false;
  for (char line[512]; std::fgets(line, sizeof line, ctl_out);) {
    out += line;
    // 0.4 s into the first chord: the robot's ACK has been heard (0.15-0.25 s after the
    // chord's start), so the pause costs no answer. PulseAudio holds about 0.4 s of the
    // chord ahead, so the hole is about 0.4 s, and the rest ends after the lockout. Both
    // sleeps kept: where the hole falls in the chord, and how long it is, are the test.
    if (!paused && out.find("transmitting") != std::string::npos) {
      std::this_thread::sleep_for(std::chrono::milliseconds(400));
      ::kill(server_, SIGSTOP);
      std::this_thread::sleep_for(std::chrono::milliseconds(460));
      ::kill(server_, SIGCONT);
      paused = true;
    }
  }
  const int status = ::pclose(ctl_out);
  const dtmf::LinkProfile& seed = dtmf::seed_profile();
  const auto split = air.split_chords(seed.timing.chord_ms, seed.words().robot_detector.bandpass_low_hz,
                                      seed.words().robot_detector.bandpass_high_hz);
  ASSERT_TRUE(paused) << out;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("drive_for_duration speed=50.0% duration=1.03s: confirmed"), std::string::npos) << out;
  // The pause did cut a chord in two, with more than 0.2 s of silence: enough to outlast
  // the 0.9 s lockout, which alone let the rest pass again.
  ASSERT_FALSE(split.empty()) << "the pause split no chord:\n" << out;
  const auto widest =
      *std::max_element(split.begin(), split.end(), [](const auto& a, const auto& b) { return a.gap_ms < b.gap_ms; });
  EXPECT_GT(widest.gap_ms, 250) << widest.first_ms << " ms, " << widest.gap_ms << " ms of silence, " << widest.second_ms
                                << " ms";

  std::ifstream log(kDir / "agent.log");
  log.seekg(static_cast<std::streamoff>(agent_log_at));
  std::size_t frames = 0;
  bool ran = false;
  for (std::string line; std::getline(log, line);) {
    frames += line.find(" seed frame ") != std::string::npos;
    ran = ran || line.find("command drive_for_duration speed=50") != std::string::npos;
  }
  EXPECT_EQ(frames, 3u) << "the robot heard " << frames << " frames of the command's 3";
  EXPECT_TRUE(ran);
}

TEST_F(DtmfctlLive, SequenceShowsProgressAndEndsWithTheSeedsReport) {
  dtmf::test_support::AirRecording air((kDir / "air.wav").string());
  const auto r = run_command(ctl("sequence --label general") + " < /dev/null");
  const dtmf::LinkProfile& seed = dtmf::seed_profile();
  const auto split = air.split_chords(seed.timing.chord_ms, seed.words().robot_detector.bandpass_low_hz,
                                      seed.words().robot_detector.bandpass_high_hz);
  for (const auto& s : split) {
    std::printf("the air split a chord %.2f s into the recording: %.0f ms, %.0f ms of silence, %.0f ms\n", s.start_s,
                s.first_ms, s.gap_ms, s.second_ms);
  }
  ASSERT_EQ(r.exit_code, 0) << r.out.substr(r.out.size() > 3000 ? r.out.size() - 3000 : 0);
  EXPECT_NE(r.out.find("65/65"), std::string::npos);
  EXPECT_NE(r.out.find("Test Results - general"), std::string::npos) << r.out.substr(r.out.size() - 2000);
  EXPECT_NE(r.out.find("Total transmission sent"), std::string::npos);

  const auto json = run_command(ctl("report --json"), false);
  ASSERT_EQ(json.exit_code, 0) << json.out;
  const auto report = whole_json_lines(json.out);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0]["label"], "general");
  EXPECT_EQ(report[0]["transmissions_sent"], 65);
  EXPECT_EQ(report[0]["successfully_matched"], 65);  // the robot logged what it heard
  EXPECT_EQ(report[0]["dropped"], 0);
  EXPECT_EQ(report[0]["sender_confirmed"], 65);
  // The seed's promise: every chord heard once, and no frame that was never sent. Even a
  // chord the air cut in two is heard once (AChordWithAHoleInItIsHeardOnce), unless its hole
  // is longer than the receiver bridges: each such one may be heard twice (an extra
  // reception, counted as a false positive), and each of them a frame that was sent.
  const long beyond_bridging = dtmf::test_support::holes_longer_than(split, seed.words().debounce.max_dropout_ms);
  EXPECT_LE(report[0]["duplicates"].get<long>(), beyond_bridging);
  EXPECT_LE(report[0]["false_positives"].get<long>(), beyond_bridging);
  // A frame the robot refused (answered NACK, executed nothing) is not one it took: a robot
  // without a key reads an authenticated frame out of other sound now and then (the seed's
  // chords too: without the key it can check only the 8-bit CRC, not the MAC) and refuses it;
  // the report counts it as refused, not accepted (migration 007).
  const std::string run_id = report[0]["run_id"];
  const auto unsent =
      run_command("psql \"$DTMF_DB_URL\" -tAc \"SELECT count(*) FROM run_receptions('" + run_id +
                      "'::uuid) r WHERE r.crc_ok AND r.event IS DISTINCT FROM 'refused' AND NOT EXISTS (SELECT 1 "
                      "FROM frame_attempts a WHERE a.run_id = '" +
                      run_id + "'::uuid AND a.frame = r.frame)\"",
                  false);
  EXPECT_EQ(unsent.out, "0\n") << "frames heard that were never sent";
  std::printf("%s\n", run_command(ctl("report")).out.c_str());

  const auto csv = run_command(ctl("report --csv"), false);
  EXPECT_EQ(csv.exit_code, 0);
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 2);
  EXPECT_EQ(csv.out.rfind("run_number,run_id,label", 0), 0u) << csv.out;
  const auto runs = run_command(ctl("runs --json"), false);
  EXPECT_EQ(whole_json_lines(runs.out).front()["label"], "general");
  if (HasFailure()) {  // what each side did and when, to tell a split chord from a wrong frame
    for (const char* log : {"agent.log", "server.log"}) {
      std::ifstream in(kDir / log);
      std::printf("%s:\n%s\n", log, std::string(std::istreambuf_iterator<char>(in), {}).c_str());
    }
  }
}

TEST_F(DtmfctlLive, WatchShowsTheAirAsADriveGoesOut) {
  const fs::path out = kDir / "watch.jsonl";
  // The first spectrum column says the watch is open; then a drive, watched for 4 s in all.
  const auto r = run_command(ctl("watch --json --spectrum --columns-per-s 2 --bins 16 --seconds 4") + " > " +
                             out.string() + " & w=$!; i=0; until [ -s " + out.string() +
                             " ] || [ $i -ge 100 ]; do sleep 0.05; i=$((i+1)); done; " +
                             ctl("drive --speed 30 --duration 1 --profile fast") + " < /dev/null && wait $w");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream file(out);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  std::vector<std::string> kinds;
  for (const auto& line : whole_json_lines(text)) {
    for (const char* kind : {"frame_played", "frame_answered", "command_ended", "spectrum"})
      if (line.contains(kind)) kinds.emplace_back(kind);
    if (line.contains("spectrum")) {
      EXPECT_EQ(line["spectrum"]["level_dbfs"].size(), 16u) << line;
    }
    if (line.contains("frame_answered")) {
      EXPECT_EQ(line["frame_answered"]["answer"], "ack") << line;
    }
  }
  for (const char* kind : {"frame_played", "frame_answered", "command_ended"})
    EXPECT_EQ(std::count(kinds.begin(), kinds.end(), kind), 1) << kind << "\n" << text;
  EXPECT_GE(std::count(kinds.begin(), kinds.end(), "spectrum"), 6) << text;  // 2 a second for 4 s
  // A bad value is a usage error naming it.
  const auto bad = run_command(ctl("watch --bins 9999"));
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_NE(bad.out.find("--bins"), std::string::npos) << bad.out;
}
