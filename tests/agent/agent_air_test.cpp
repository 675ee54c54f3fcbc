// dtmf-agent live, over real audio: the PulseAudio "air" (scripts/air, started by the ctest
// fixture). A sender plays chords into the air with paplay, the agent hears them through
// PortAudio and answers into the same air, and a recording of the air holds both.
#include <gtest/gtest.h>

#include <filesystem>

#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "signal/tone_listener.h"
#include "support/run_command.h"

using namespace dtmf;
using test_support::json_lines;
using test_support::run_command;

namespace {

std::vector<signal::Heard> hear(signal::ToneListener listener, const std::vector<float>& audio) {
  std::vector<signal::Heard> heard;
  for (const auto& h : listener.feed(audio)) heard.push_back(h);
  return heard;
}

}  // namespace

TEST(AgentAir, HearsChordsFromTheAirAnswersIntoItAndDrives) {
  ASSERT_NE(std::getenv("PULSE_SERVER"), nullptr) << "needs the air (ctest fixture)";
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("agent-air-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string x = (dir / "x.wav").string(), rec = (dir / "air.wav").string();
  const std::string out = (dir / "agent.out").string(), err = (dir / "agent.err").string();
  ASSERT_EQ(run_command(std::string(DTMFCTL_PATH) + " encode --wav " + x + " drive --speed 50 --duration 1").exit_code,
            0);

  const std::string script =
      std::string(DTMF_AGENT_PATH) + " --audio default --ack-out default --cmd-vel log --db none > " + out + " 2> " +
      err +
      " & agent=$!; "
      "parecord --device=air.monitor --rate=48000 --channels=1 --file-format=wav " +
      rec +
      " & recorder=$!; "
      // The chords start once the agent listens, plus 0.5 s: a fixed 1.5 s was not always
      // enough for a loaded machine, and an agent that starts mid-chord hears a fragment.
      "for i in $(seq 200); do grep -q 'audio threads' " +
      err +
      " && break; sleep 0.1; done; "
      "sleep 0.5; paplay --device=air " +
      x +
      "; sleep 2; "
      "kill -INT $recorder; kill -TERM $agent; wait $agent; status=$?; wait $recorder; exit $status";
  const auto r = run_command(script);
  const auto agent_log = run_command("cat " + err).out;
  ASSERT_EQ(r.exit_code, 0) << r.out << agent_log;

  // The agent: three frames heard, a drive at 0.11 m/s, stopped at the end.
  EXPECT_NE(agent_log.find("3 frames heard"), std::string::npos) << agent_log;
  const auto lines = json_lines(run_command("cat " + out).out);
  ASSERT_FALSE(lines.empty()) << agent_log;
  int moving = 0;
  for (const auto& line : lines) moving += line["linear_mps"] == 0.11 ? 1 : 0;
  EXPECT_GT(moving, 15) << agent_log;  // about 1 s at 20 Hz
  EXPECT_EQ(lines.back()["linear_mps"], 0.0);

  // The air: the sender's three chords and the agent's three ACKs, each after its chord.
  const auto air = physical::read_audio_file(rec, seed_profile().sample_rate_hz);
  const auto chords = hear(signal::chord_listener(seed_profile()), air);
  const auto replies = hear(signal::reply_listener(seed_profile()), air);
  ASSERT_EQ(chords.size(), 3u);
  ASSERT_EQ(replies.size(), 3u) << agent_log;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(static_cast<signal::Reply>(replies[i].symbol), signal::Reply::Ack);
    const double response_ms = replies[i].heard_ms - chords[i].start_ms;
    std::printf("frame %zu: chord at %.0f ms, ACK heard %.0f ms after it\n", i, chords[i].start_ms, response_ms);
    EXPECT_GT(response_ms, 0);
    EXPECT_LT(response_ms, seed_profile().timing.ack_timeout_ms);
  }
  std::filesystem::remove_all(dir);
}
