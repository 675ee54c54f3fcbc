// dtmf-bench-decoder: how fast the robot's receive path decodes, per link profile.
//
// Feeds the robot's receiver (link/frame_trials.h: the whole receive path — window,
// spectrum, peaks or symbols, debouncing, the check) in 1024-sample blocks, as a live
// microphone would, and reports seconds of audio decoded per second of one core's CPU time
// (CLOCK_THREAD_CPUTIME_ID, so the figure is one core's whatever else the machine does).
// Two signals:
//   noise:  60 s of pink noise at -30 dBFS, nothing to find (the robot's usual day);
//   frames: random frames back to back (chord + gap each) in pink noise at -40 dBFS;
//           every frame must be accepted, or the figure would flatter.
// Prints one line per signal; --json PATH writes both.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <random>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "common/thread_cpu.h"
#include "frames/frame_trials.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "sim/noise.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr std::size_t kBlockSamples = 1024;
constexpr double kNoiseOnlyDbfs = -30;
constexpr double kUnderFramesDbfs = -40;

std::vector<float> noise_only(const LinkProfile& profile, double audio_s) {
  std::vector<float> audio(static_cast<std::size_t>(audio_s * profile.sample_rate_hz), 0.0f);
  sim::NoiseSource(sim::parse_noise("pink", kNoiseOnlyDbfs), profile.sample_rate_hz, 1).add_to(audio);
  return audio;
}

// Random frames back to back, as many as fit in `audio_s` (at least one), in quiet noise.
std::pair<std::vector<float>, std::size_t> back_to_back_frames(FrameTrials& trials, double audio_s) {
  const LinkProfile& profile = trials.profile();
  const std::size_t count =
      std::max<std::size_t>(1, static_cast<std::size_t>(audio_s * profile.sample_rate_hz) / trials.slot_samples());
  std::vector<float> audio(count * trials.slot_samples(), 0.0f);
  std::mt19937_64 rng(7);
  for (std::size_t i = 0; i < count; ++i) {
    FrameTrials::add_frame(trials.random_frame(rng), std::span<float>(audio).subspan(i * trials.slot_samples()));
  }
  sim::NoiseSource(sim::parse_noise("pink", kUnderFramesDbfs), profile.sample_rate_hz, 2).add_to(audio);
  return {audio, count};
}

struct Measurement {
  double audio_s;
  double cpu_s;
  std::size_t accepted;
};

Measurement decode(const link::Link& robot, const std::vector<float>& audio) {
  const LinkProfile& profile = robot.profile();
  FrameReceiver receiver(robot);
  std::vector<Accepted> accepted;
  accepted.reserve(audio.size() / 1000);
  const double start = thread_cpu_s();
  for (std::size_t at = 0; at < audio.size(); at += kBlockSamples) {
    receiver.feed(std::span<const float>(audio).subspan(at, std::min(kBlockSamples, audio.size() - at)), accepted);
  }
  return {static_cast<double>(audio.size()) / profile.sample_rate_hz, thread_cpu_s() - start, accepted.size()};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-decoder: seconds of audio the robot's receive path decodes per CPU second");
  std::string profile_name = "seed", json_path;
  double audio_s = 60;
  bool list_profiles = false;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--audio-s", audio_s, "seconds of audio per signal")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("--list-profiles", list_profiles,
               "print every profile's name, one a line, and after each whose frames can carry a MAC the same "
               "name with \"+key\" (its authenticated frames: scripts/bench runs both), and exit");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        if (list_profiles) {
          for (const LinkProfile* p : all_profiles()) {
            std::printf("%s\n", p->name.c_str());
            if (link::make_link(*p)->can_authenticate()) std::printf("%s+key\n", p->name.c_str());
          }
          return 0;
        }
        const LinkProfile& profile = profile_by_name(profile_name);
        FrameTrials trials(profile, bench_key(authenticated));
        const auto [frames_audio, frames] = back_to_back_frames(trials, audio_s);
        nlohmann::json doc{{"benchmark", "decoder"},
                           {"profile", profile.name},
                           {"authenticated", authenticated},
                           {"block_samples", kBlockSamples},
                           {"signals", nlohmann::json::array()}};
        int status = 0;
        for (const auto& [signal_name, audio, expected] :
             {std::tuple{"noise", noise_only(profile, audio_s), std::size_t{0}},
              std::tuple{"frames", frames_audio, frames}}) {
          const Measurement m = decode(trials.robot(), audio);
          const double speed = m.audio_s / m.cpu_s;
          std::printf(
              "decoder speed  %-6s %-7s %6.1f s of audio in %6.3f s CPU: %8.0f x real time, %zu of %zu frames "
              "accepted\n",
              profile.name.c_str(), signal_name, m.audio_s, m.cpu_s, speed, m.accepted, expected);
          doc["signals"].push_back({{"signal", signal_name},
                                    {"audio_s", m.audio_s},
                                    {"cpu_s", m.cpu_s},
                                    {"realtime_factor", speed},
                                    {"frames_expected", expected},
                                    {"frames_accepted", m.accepted}});
          if (m.accepted != expected) {
            std::fprintf(stderr, "dtmf-bench-decoder: profile %s accepted %zu frames in the %s signal, expected %zu\n",
                         profile.name.c_str(), m.accepted, signal_name, expected);
            status = 1;
          }
        }
        write_json(json_path, doc);
        return status;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-decoder: %s\n", why.c_str()); });
}
