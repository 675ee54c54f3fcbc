// dtmf-bench-distance: frame success and wrong accepts against distance in a simulated room.
//
// Random frames (chord + gap each) are played by a loudspeaker `d` metres from the robot's
// microphone through sim::AcousticChannel: propagation delay, 1/d spreading, air
// absorption, a Schroeder room (RT60 0.3 s, wet 0.3 by default) and a fixed background noise
// (pink, -50 dBFS RMS by default: a quiet room; the chords are -11 dBFS RMS at 1 m). The
// robot's receiver is fed in 1024-sample blocks and every slot is scored as in the SNR sweep
// (link/stream_trial.h). --json PATH writes the points.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/sweep.h"
#include "frames/sweep_flags.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;
using namespace dtmf::bench;

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-distance: frame success and wrong accepts against distance in a simulated room");
  std::string profile_name = "seed", json_path, noise_kind = "pink";
  std::vector<double> distances_m;
  double from_m = 1, to_m = 20, step_m = 1, noise_dbfs = -50, rt60_s = 0.3, wet = 0.3;
  SweepOptions options;
  options.threads = default_threads();
  options.topup_frames = 0;  // distance points get the same count each
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--from-m", from_m, "nearest distance")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--to-m", to_m, "farthest distance")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--step-m", step_m, "distance step")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--distance-m", distances_m, "these distances instead of the range (repeatable)");
  app.add_option("--noise", noise_kind, "background noise: white, pink or none")->capture_default_str();
  app.add_option("--noise-dbfs", noise_dbfs, "background noise level, dBFS RMS")->capture_default_str();
  app.add_option("--rt60-s", rt60_s, "the room's reverberation time (0: none)")->capture_default_str();
  app.add_option("--wet", wet, "reverberant level against the direct sound")->capture_default_str();
  add_sweep_flags(app, options, "point", true);
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        options.key = bench_key(authenticated);
        if (noise_kind != "white" && noise_kind != "pink" && noise_kind != "none") {
          throw std::invalid_argument("--noise must be white, pink or none, not '" + noise_kind + "'");
        }
        if (distances_m.empty()) {
          for (double d = from_m; d <= to_m + 1e-9; d += step_m) distances_m.push_back(std::round(d * 1000) / 1000);
        }
        std::sort(distances_m.begin(), distances_m.end());
        std::printf(
            "dtmf-bench-distance: profile %s, seed %llu, %zu frames per point, %s noise at %g dBFS RMS, "
            "RT60 %g s (wet %g), %u threads\n",
            profile.name.c_str(), static_cast<unsigned long long>(options.seed), options.frames, noise_kind.c_str(),
            noise_dbfs, rt60_s, wet, options.threads);
        std::fflush(stdout);

        const auto started = std::chrono::steady_clock::now();
        const auto points =
            run_sweep(profile, distances_m, options, [&](double distance_m, std::uint64_t seed) -> Channel {
              sim::ChannelConfig config;
              config.noise = sim::parse_noise(noise_kind, noise_dbfs);
              config.reverb = {rt60_s, wet};
              config.seed = seed;
              auto room = std::make_shared<sim::AcousticChannel>(profile.sample_rate_hz, config);
              room->add_transmitter(distance_m);
              return [room](std::span<const float> clean, std::vector<float>& heard) { room->process(clean, heard); };
            });
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;

        print_points(points, "distance (m)");
        const nlohmann::json d99 = threshold(points, 0.99, false), d999 = threshold(points, 0.999, false);
        std::printf("farthest distance with >= 99 %% success up to it: %s m; with >= 99.9 %%: %s m; %.1f s\n",
                    d99.dump().c_str(), d999.dump().c_str(), took.count());

        nlohmann::json doc{{"benchmark", "distance"},
                           {"profile", profile.name},
                           {"authenticated", authenticated},
                           {"seed", options.seed},
                           {"frames_per_point", options.frames},
                           {"block_samples", options.block_samples},
                           {"threads", options.threads},
                           {"noise", noise_kind},
                           {"noise_dbfs", noise_dbfs},
                           {"rt60_s", rt60_s},
                           {"wet", wet},
                           {"farthest_m_99", d99},
                           {"farthest_m_99_9", d999},
                           {"wall_s", took.count()},
                           {"points", nlohmann::json::array()}};
        for (const auto& p : points) doc["points"].push_back(point_json(p, "distance_m"));
        write_json(json_path, doc);
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-distance: %s\n", why.c_str()); });
}
