// Benchmark: how fast the robot's receive path decodes, per link profile.
//
// Feeds the robot's chord listener (signal layer: window, spectrum, peaks, chord decoder,
// debouncer) in 10 ms blocks, as a live microphone would, and reports seconds of audio
// decoded per second of one core's CPU time (CLOCK_THREAD_CPUTIME_ID, so the figure is
// one core's whatever else the machine does). Two signals per profile:
//   noise:  60 s of pink noise at -30 dBFS, nothing to find (the robot's usual day);
//   frames: the seed's test sequence (65 frames) back to back in pink noise at -40 dBFS,
//           repeated to 60 s; every frame must be heard, or the figure would flatter.
// Prints one line per measurement, or JSON lines with --json (for scripts/bench).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <ctime>

#include "command/test_sequence.h"
#include "link/sender_path.h"
#include "physical/noise.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "signal/tone_listener.h"

using namespace dtmf;

namespace {

constexpr double kAudioS = 60;
constexpr double kBlockMs = 10;

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

std::vector<float> noise_only(const LinkProfile& profile) {
  std::vector<float> audio(static_cast<std::size_t>(kAudioS * profile.sample_rate_hz), 0.0f);
  physical::NoiseSource(physical::parse_noise("pink", -30), profile.sample_rate_hz, 1).add_to(audio);
  return audio;
}

// Returns the audio and how many frames it holds.
std::pair<std::vector<float>, std::size_t> back_to_back_frames(const LinkProfile& profile) {
  std::vector<link::PlannedFrame> sequence;
  for (const auto& command : command::seed_test_sequence()) {
    for (const auto& f : link::plan_command(profile, command)) sequence.push_back(f);
  }
  const std::vector<float> once = link::render_frames(profile, sequence);
  std::vector<float> audio;
  std::size_t frames = 0;
  while (audio.size() + once.size() <= static_cast<std::size_t>(kAudioS * profile.sample_rate_hz) || frames == 0) {
    audio.insert(audio.end(), once.begin(), once.end());
    frames += sequence.size();
  }
  physical::NoiseSource(physical::parse_noise("pink", -40), profile.sample_rate_hz, 2).add_to(audio);
  return {audio, frames};
}

struct Measurement {
  double audio_s;
  double cpu_s;
  std::size_t heard;
};

Measurement decode(const LinkProfile& profile, const std::vector<float>& audio) {
  auto listener = signal::chord_listener(profile);
  const auto block = static_cast<std::size_t>(profile.samples_for_ms(kBlockMs));
  std::size_t heard = 0;
  const double start = thread_cpu_s();
  for (std::size_t at = 0; at < audio.size(); at += block) {
    heard += listener.feed(std::span<const float>(audio).subspan(at, std::min(block, audio.size() - at))).size();
  }
  return {static_cast<double>(audio.size()) / profile.sample_rate_hz, thread_cpu_s() - start, heard};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-decoder: seconds of audio the robot's receive path decodes per CPU second");
  bool json = false;
  std::vector<std::string> profiles;
  app.add_flag("--json", json, "one JSON object per measurement");
  app.add_option("--profile", profiles, "profiles to measure (default: all: " + profile_names() + ")");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run([&] {
    if (profiles.empty()) {
      for (const LinkProfile* p : all_profiles()) profiles.push_back(p->name);
    }
    for (const std::string& name : profiles) {
      const LinkProfile& profile = profile_by_name(name);
      const auto [frames_audio, frames] = back_to_back_frames(profile);
      for (const auto& [signal_name, audio, expected] :
           {std::tuple{"noise", noise_only(profile), std::size_t{0}}, std::tuple{"frames", frames_audio, frames}}) {
        const Measurement m = decode(profile, audio);
        const double speed = m.audio_s / m.cpu_s;
        if (json) {
          std::printf("%s\n", nlohmann::json{{"benchmark", "decoder_speed"}, {"profile", name}, {"signal", signal_name},
                                             {"audio_s", m.audio_s}, {"cpu_s", m.cpu_s}, {"realtime_factor", speed},
                                             {"frames_expected", expected}, {"frames_heard", m.heard}}
                                  .dump()
                                  .c_str());
        } else {
          std::printf("decoder speed  %-6s %-7s %6.1f s of audio in %6.3f s CPU: %8.0f x real time, %zu of %zu frames heard\n",
                      name.c_str(), signal_name, m.audio_s, m.cpu_s, speed, m.heard, expected);
        }
        if (m.heard != expected) {
          std::fprintf(stderr, "decoder speed: profile %s heard %zu frames in the %s signal, expected %zu\n",
                       name.c_str(), m.heard, signal_name, expected);
          return 1;
        }
      }
    }
    return 0;
  }, [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-decoder: %s\n", why.c_str()); });
}
