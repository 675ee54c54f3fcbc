// dtmf-bench-snr: frame success and wrong accepts against SNR in white Gaussian noise.
//
// SNR = mean power of the transmitted signal over its non-silent part (the chords, measured
// from random frames) / power of the added white Gaussian noise over the full band 0..fs/2,
// in dB. For each SNR (default -30 to +20 dB in 2 dB steps) continuous streams of random
// frames (chord + gap each) get noise over the whole stream and go to the robot's receiver in
// 1024-sample blocks; each slot is scored (link/stream_trial.h). Points whose success lands
// between 90 % and 99.99 % after the first frames are topped up (link/sweep.h). No clipping:
// the channel is linear, so at -30 dB the noise is far louder than full scale.
// Prints a table and the lowest SNR with >= 99 % and >= 99.9 % success; --json PATH writes it all.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "common/gaussian.h"
#include "frames/sweep.h"
#include "frames/sweep_flags.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "units/decibels.h"

using namespace dtmf;
using namespace dtmf::bench;

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-snr: frame success and wrong accepts against SNR (white Gaussian noise)");
  std::string profile_name = "seed", json_path;
  double from_db = -30, to_db = 20, step_db = 2;
  std::vector<double> snrs_db;
  SweepOptions options;
  options.threads = default_threads();
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--from-db", from_db, "lowest SNR")->capture_default_str();
  app.add_option("--to-db", to_db, "highest SNR")->capture_default_str();
  app.add_option("--step-db", step_db, "SNR step")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--snr-db", snrs_db, "these SNRs instead of the range (repeatable)");
  add_sweep_flags(app, options, "point", true);
  app.add_option("--topup-frames", options.topup_frames, "frames at points near the thresholds")->capture_default_str();
  app.add_option("--topup-low", options.topup_low, "top up points with success at least this ...")
      ->capture_default_str();
  app.add_option("--topup-high", options.topup_high, "... and below this")->capture_default_str();
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        options.key = bench_key(authenticated);
        if (snrs_db.empty()) {
          for (double s = from_db; s <= to_db + 1e-9; s += step_db) snrs_db.push_back(std::round(s * 1000) / 1000);
        }
        std::sort(snrs_db.begin(), snrs_db.end());
        FrameTrials trials(profile, options.key);
        const double signal_power = mean_sound_power(trials, 256, options.seed);
        std::printf(
            "dtmf-bench-snr: profile %s, seed %llu, %zu frames per point (up to %zu near the thresholds), "
            "%u threads\n  signal power over the chords %.4f (%.2f dBFS RMS, a full-scale sine = -3.01)\n",
            profile.name.c_str(), static_cast<unsigned long long>(options.seed), options.frames, options.topup_frames,
            options.threads, signal_power, units::db_from_power_ratio(signal_power));
        std::fflush(stdout);

        const auto started = std::chrono::steady_clock::now();
        const auto points = run_sweep(profile, snrs_db, options, [&](double snr_db, std::uint64_t seed) -> Channel {
          const auto sigma = static_cast<float>(std::sqrt(signal_power / units::power_ratio_from_db(snr_db)));
          return [sigma, noise = std::make_shared<GaussianNoise>(seed)](std::span<const float> clean,
                                                                        std::vector<float>& heard) {
            heard.assign(clean.begin(), clean.end());
            noise->add_to(heard, sigma);
          };
        });
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;

        print_points(points, "SNR (dB)");
        const nlohmann::json t99 = threshold(points, 0.99, true), t999 = threshold(points, 0.999, true);
        std::uint64_t total_frames = 0, total_wrong = 0;
        for (const auto& p : points) total_frames += p.counts.frames, total_wrong += p.counts.wrong_accepts;
        std::printf(
            "lowest SNR with >= 99 %% success: %s dB; with >= 99.9 %%: %s dB\n"
            "%llu frames, %llu wrong accepts in all, %.1f s (%.0f s of audio per second)\n",
            t99.dump().c_str(), t999.dump().c_str(), static_cast<unsigned long long>(total_frames),
            static_cast<unsigned long long>(total_wrong), took.count(),
            static_cast<double>(total_frames) * trials.slot_samples() / profile.sample_rate_hz / took.count());

        nlohmann::json doc{{"benchmark", "snr"},
                           {"profile", profile.name},
                           {"authenticated", authenticated},
                           {"seed", options.seed},
                           {"frames_per_point", options.frames},
                           {"topup_frames", options.topup_frames},
                           {"topup_band", {options.topup_low, options.topup_high}},
                           {"block_samples", options.block_samples},
                           {"chunk_frames", options.chunk_frames},
                           {"threads", options.threads},
                           {"sample_rate_hz", profile.sample_rate_hz},
                           {"slot_ms", profile.timing.chord_ms + profile.timing.gap_ms},
                           {"signal_power", signal_power},
                           {"signal_rms_dbfs", units::db_from_power_ratio(signal_power)},
                           {"lowest_snr_db_99", t99},
                           {"lowest_snr_db_99_9", t999},
                           {"total_frames", total_frames},
                           {"total_wrong_accepts", total_wrong},
                           {"wall_s", took.count()},
                           {"points", nlohmann::json::array()}};
        for (const auto& p : points) doc["points"].push_back(point_json(p, "snr_db"));
        write_json(json_path, doc);
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-snr: %s\n", why.c_str()); });
}
