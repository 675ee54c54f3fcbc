// dtmf-agent run as a user runs it, offline: a recording in, velocities and answers out,
// and bad recordings that must give a clear result without a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
#include "support/run_command.h"

using namespace dtmf;
using test_support::json_lines;
using test_support::run_command;
namespace fs = std::filesystem;

namespace {

class AgentOffline : public ::testing::Test {
 protected:
  fs::path dir_ = fs::path(::testing::TempDir()) / ("agent-" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // dtmf-agent offline on `wav`; stdout only (the JSON lines) unless with_logs.
  test_support::CommandResult agent(const std::string& wav, const std::string& extra = "", bool with_logs = false) {
    return run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + wav + " --cmd-vel log --db none " + extra,
                       with_logs);
  }
  void encode(const std::string& args, const std::string& wav) {
    ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " encode --wav " + wav + " " + args).exit_code, 0);
  }
};

}  // namespace

// The issue's acceptance run: drive at 50 % for 2 s.
TEST_F(AgentOffline, DrivesAbout011MpsForAbout2SecondsThenZeroAndAcksEveryFrame) {
  encode("drive --speed 50 --duration 2", path("x.wav"));
  const auto r = agent(path("x.wav"), "--ack-out wav:" + path("y.wav"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto lines = json_lines(r.out);
  ASSERT_GT(lines.size(), 40u);
  double first_move = -1, last_move = -1;
  for (const auto& line : lines) {
    const double v = line["linear_mps"];
    if (v != 0) {
      EXPECT_NEAR(v, 0.11, 0.22 * 100.0 / 62 / 100);  // within one 6-bit speed step
      if (first_move < 0) first_move = line["t_ms"];
      last_move = line["t_ms"];
    }
    EXPECT_EQ(line["angular_radps"], 0.0);
  }
  ASSERT_GE(first_move, 0) << r.out;
  const double moved_s = (last_move - first_move) / 1000.0 + 0.05;  // plus the last period
  EXPECT_NEAR(moved_s, 2.0, 8.0 / 62);                              // within one duration step
  EXPECT_EQ(lines.back()["linear_mps"], 0.0);

  const auto acks = physical::read_audio_file(path("y.wav"), seed_profile().sample_rate_hz);
  auto listener = signal::reply_listener(seed_profile());
  std::vector<signal::Heard> heard;
  for (const auto& h : listener.feed(acks)) heard.push_back(h);
  ASSERT_EQ(heard.size(), 3u);
  for (const auto& h : heard) EXPECT_EQ(static_cast<signal::Reply>(h.symbol), signal::Reply::Ack);
}

// Issue [2/3]: a velocity frame shows on cmd_vel, held for its lease, then ramps to zero.
TEST_F(AgentOffline, AVelocityHoldsForItsLeaseThenTheWheelsStop) {
  encode("--profile fast velocity --linear-mps -0.05 --angular-radps 0.4 --lease-s 0.5", path("v.wav"));
  const auto r = agent(path("v.wav"), "", true);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto lines = json_lines(r.out);
  double first_move = -1, last_move = -1;
  for (const auto& line : lines) {
    const double linear = line["linear_mps"], angular = line["angular_radps"];
    if (linear == 0 && angular == 0) continue;
    if (first_move < 0) first_move = line["t_ms"];
    last_move = line["t_ms"];
    if (line["t_ms"].get<double>() < 450) {  // held, not yet ramping down
      EXPECT_NEAR(linear, -0.05, 0.0001) << "reverse, at the payload's resolution";
      EXPECT_NEAR(angular, 0.4, 2.84 / 127);
    }
  }
  ASSERT_GE(first_move, 0) << r.out;
  // The lease, 0.5 s (exact in the frame's field), runs from the frame's start (the
  // recording's first chord, at 0 s), not from when it was heard: once a 40 ms window lies
  // wholly inside its last chord (which begins at 51.25 ms, after a 0.5 ms fade), so at
  // 91.75 ms at the earliest (the recording begins with the frame: no window lies astride its
  // start, as in the test below), and by its end (102.5 ms) at the latest.
  // The robot places the start where the first chord's tones rose, and
  // the wheels stand still at the lease's end: the ramp down (0.4 / 25 = 16 ms) ends by
  // about 520 ms, so with cmd_vel sampled every 50 ms the last motion is at 450 or 500 ms.
  EXPECT_GE(first_move, 51.25 + 0.5 + 40 - 0.5) << "moved before its last chord could be read";
  EXPECT_LE(first_move, 102.5 + 10.25) << "heard late";
  EXPECT_GE(last_move, 450) << r.out;
  EXPECT_LE(last_move, 500) << r.out;
  // The standstill itself is published when it comes, not at the next 50 ms tick (550 ms).
  const auto zero = std::find_if(lines.begin(), lines.end(), [&](const nlohmann::json& line) {
    return line["t_ms"].get<double>() > last_move && line["linear_mps"] == 0.0 && line["angular_radps"] == 0.0;
  });
  ASSERT_NE(zero, lines.end()) << r.out;
  EXPECT_LT((*zero)["t_ms"].get<double>(), 530) << r.out;
  EXPECT_EQ(lines.back()["linear_mps"], 0.0);
  EXPECT_EQ(lines.back()["angular_radps"], 0.0);
  EXPECT_NE(r.out.find("stop: lease ended"), std::string::npos) << r.out;
}

// After silence, a clean frame decodes from windows astride its chords' starts, about 40 ms
// before it ends; the lease still runs from the frame's first chord (the robot's start is
// where its tones rose, not the decoding window's place), so the wheels stop 0.5 s after it.
TEST_F(AgentOffline, AVelocityHeardBeforeItsFrameEndsHoldsItsLeaseFromTheFrameStart) {
  encode("--profile fast velocity --linear-mps 0.1 --angular-radps 0 --lease-s 0.5", path("v.wav"));
  const LinkProfile& fast = fast_profile();
  std::vector<float> audio(static_cast<std::size_t>(fast.samples_for_ms(300)), 0.0f);  // the frame at 300 ms
  const auto frame = physical::read_audio_file(path("v.wav"), fast.sample_rate_hz);
  audio.insert(audio.end(), frame.begin(), frame.end());
  physical::write_wav_file(path("late.wav"), audio, fast.sample_rate_hz);
  const auto r = agent(path("late.wav"), "", true);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto lines = json_lines(r.out);
  const auto moving = [](const nlohmann::json& line) { return line["linear_mps"].get<double>() != 0.0; };
  std::smatch heard;
  ASSERT_TRUE(std::regex_search(r.out, heard, std::regex(R"(t=([0-9.]+)s fast frame \S+ seq \d+: ACK)"))) << r.out;
  EXPECT_LT(std::stod(heard[1]) * 1000, 300 + 102.5) << "decided before the frame ended";
  const auto first = std::find_if(lines.begin(), lines.end(), moving);
  ASSERT_NE(first, lines.end()) << r.out;
  const auto stopped = std::find_if(first, lines.end(), [&](const nlohmann::json& line) { return !moving(line); });
  ASSERT_NE(stopped, lines.end()) << r.out;
  // 0.1 m/s ramps down at the model's 2.5 m/s^2 in 40 ms, timed to reach zero at the lease's end.
  EXPECT_NEAR((*stopped)["t_ms"].get<double>(), 300 + 500, 3) << r.out;
}

TEST_F(AgentOffline, ACorruptedChordIsNackedAndNothingMoves) {
  // A real command whose parameter chord gets one tone moved: the CRC no longer fits.
  const auto sent =
      run_command(std::string(DTMFCTL_PATH) + " encode --json --wav " + path("good.wav") + " drive --speed 80");
  const auto frames = json_lines(sent.out);
  ASSERT_EQ(frames.size(), 3u);
  auto audio = physical::read_audio_file(path("good.wav"), 48000);
  std::vector<double> tones = frames[2]["tones_hz"];
  const double step = seed_profile().words().tones.step_hz;
  tones[3] += tones[3] + step < 16001 ? step : -step;  // the CRC nibble one off
  const LinkProfile& p = seed_profile();
  const auto start = static_cast<std::size_t>(p.samples_for_ms(2000));
  std::fill(audio.begin() + static_cast<long>(start), audio.begin() + static_cast<long>(start) + p.samples_for_ms(800),
            0.0f);
  signal::add_chord(std::span(audio).subspan(start, static_cast<std::size_t>(p.samples_for_ms(800))), tones,
                    p.words().tones.tone_amplitude, p.words().tones.edge_ms, p.sample_rate_hz);
  physical::write_wav_file(path("bad.wav"), audio, 48000);

  const auto r = agent(path("bad.wav"), "--ack-out wav:" + path("acks.wav"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const auto& line : json_lines(r.out)) EXPECT_EQ(line["linear_mps"], 0.0);
  auto listener = signal::reply_listener(p);
  std::vector<signal::Reply> replies;
  for (const auto& h : listener.feed(physical::read_audio_file(path("acks.wav"), 48000))) {
    replies.push_back(static_cast<signal::Reply>(h.symbol));
  }
  EXPECT_EQ(replies, (std::vector<signal::Reply>{signal::Reply::Ack, signal::Reply::Ack, signal::Reply::Nack}));
}

TEST_F(AgentOffline, StereoAnd44kRecordingsWork) {
  encode("turn --rotation 50 --duration 1", path("t.wav"));
  ASSERT_EQ(run_command("sox " + path("t.wav") + " -r 44100 -c 2 " + path("t44s.wav")).exit_code, 0);
  const auto r = agent(path("t44s.wav"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  bool turned = false;
  for (const auto& line : json_lines(r.out))
    turned = turned || std::abs(line["angular_radps"].get<double>() - 1.42) < 0.05;
  EXPECT_TRUE(turned) << r.out;
}

TEST_F(AgentOffline, AnEmptyRecordingHearsNothingAndStopsTheRobot) {
  physical::write_wav_file(path("empty.wav"), {}, 48000);
  const auto r = agent(path("empty.wav"), "", true);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("0 frames heard"), std::string::npos) << r.out;
  const auto lines = json_lines(r.out);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back()["linear_mps"], 0.0);
}

TEST_F(AgentOffline, NonAudioAndTooSlowRecordingsAreRefusedClearly) {
  std::ofstream(path("notes.wav")) << "not audio\n";
  auto r = agent(path("notes.wav"), "", true);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find(path("notes.wav")), std::string::npos) << r.out;
  physical::write_wav_file(path("8k.wav"), std::vector<float>(8000, 0.0f), 8000);
  r = agent(path("8k.wav"), "", true);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("8000 Hz"), std::string::npos) << r.out;
  r = agent(path("missing.wav"), "", true);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("missing.wav"), std::string::npos) << r.out;
}

TEST_F(AgentOffline, TenMinutesOfNoiseHearNothingInBoundedMemory) {
  ASSERT_EQ(run_command("sox -n -r 48000 -c 1 " + path("noise.wav") + " synth 600 whitenoise vol 0.3").exit_code, 0);
  const auto r = agent(path("noise.wav"), "", true);
  EXPECT_EQ(r.exit_code, 0) << r.out.substr(0, 2000);
  EXPECT_NE(r.out.find("0 frames heard in 600.0 s"), std::string::npos) << r.out.substr(r.out.size() - 500);
  // The recording is 110 MiB of samples; the agent streams it.
  EXPECT_LT(test_support::max_child_rss_mib(), 100.0);
}

TEST_F(AgentOffline, BadFlagsAreUsageErrors) {
  EXPECT_EQ(run_command(std::string(DTMF_AGENT_PATH) + " --robot roomba").exit_code, 2);
  EXPECT_EQ(run_command(std::string(DTMF_AGENT_PATH) + " --cmd-vel teleport").exit_code, 2);
  EXPECT_EQ(run_command(std::string(DTMF_AGENT_PATH) + " --publish-rate-hz 0").exit_code, 2);
  // The buffer depth is the program's flag (and environment variable), checked before any device opens.
  const auto shallow = run_command(std::string(DTMF_AGENT_PATH) + " --audio-buffer-ms 1");
  EXPECT_EQ(shallow.exit_code, 2) << shallow.out;
  EXPECT_NE(shallow.out.find("--audio-buffer-ms"), std::string::npos) << shallow.out;
  const auto from_env = run_command("DTMF_AUDIO_BUFFER_MS=9000 " + std::string(DTMF_AGENT_PATH) + " --db none");
  EXPECT_EQ(from_env.exit_code, 2) << from_env.out;
  EXPECT_NE(from_env.out.find("9000"), std::string::npos) << from_env.out;
  const auto version = run_command(std::string(DTMF_AGENT_PATH) + " --version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, std::string("dtmf-agent ") + DTMF_VERSION + "\n");
  const auto help = run_command(std::string(DTMF_AGENT_PATH) + " --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* word : {"--audio", "--ack-out", "--cmd-vel", "--profile", "--list-audio-devices", "--db",
                           "--continuous-limit-s", "Exit codes"}) {
    EXPECT_NE(help.out.find(word), std::string::npos) << word;
  }
}

TEST_F(AgentOffline, AnUnreachableDatabaseStopsTheAgentBeforeItListens) {
  encode("stop", path("s.wav"));
  const auto r = run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + path("s.wav") +
                             " --cmd-vel log --db postgresql://postgres@127.0.0.1:1/x");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("cannot reach the database"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--db none"), std::string::npos) << r.out;
}

TEST_F(AgentOffline, NoAudioDeviceStopsTheAgentWithWhatToDo) {
  const auto r = run_command("PULSE_SERVER=unix:/nonexistent " + std::string(DTMF_AGENT_PATH) +
                             " --audio default --cmd-vel log --db none");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("no audio device found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wav:FILE"), std::string::npos) << r.out;
}

// The sender's ear offline: the agent's answers to a fast sequence, written to a WAV, read
// back by `dtmfctl decode --replies`: one ACK per frame, each naming that frame's sequence
// number, in order; and a seed drive's three ACKs.
TEST_F(AgentOffline, DecodeRepliesHearsTheAgentsAnswersNamingEachFrame) {
  const auto sent = json_lines(
      run_command(std::string(DTMFCTL_PATH) + " encode --json --profile fast --wav " + path("f.wav") + " sequence")
          .out);
  ASSERT_EQ(sent.size(), 27u);
  ASSERT_EQ(agent(path("f.wav"), "--profile fast --ack-out wav:" + path("f_acks.wav")).exit_code, 0);
  const auto r =
      run_command(std::string(DTMFCTL_PATH) + " decode --json --replies --profile fast " + path("f_acks.wav"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), sent.size()) << r.out;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(replies[i]["reply"], "ack") << i;
    EXPECT_EQ(replies[i]["sequence"], sent[i]["sequence"]) << i;
    if (i > 0) {
      EXPECT_GT(replies[i]["t_ms"].get<double>(), replies[i - 1]["t_ms"].get<double>());
    }
  }

  encode("drive --speed 50 --duration 2", path("s.wav"));
  ASSERT_EQ(agent(path("s.wav"), "--profile seed --ack-out wav:" + path("s_acks.wav")).exit_code, 0);
  const auto human = run_command(std::string(DTMFCTL_PATH) + " decode --replies " + path("s_acks.wav"));
  ASSERT_EQ(human.exit_code, 0) << human.out;
  EXPECT_NE(human.out.find("3 ACKs, 0 NACKs heard (profile seed)"), std::string::npos) << human.out;
  // The frames themselves are no replies: decoding the commands' recording as replies hears none.
  const auto none = run_command(std::string(DTMFCTL_PATH) + " decode --replies " + path("s.wav"));
  EXPECT_NE(none.out.find("0 ACKs, 0 NACKs heard"), std::string::npos) << none.out;
}
