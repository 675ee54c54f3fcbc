// dtmf-bench-rooms: frame success in real rooms — measured, image-source, with frequency
// offsets and whines — one row per case, the rooms table of docs/benchmarks.md.
//
// A case is a name and the channel flags of `dtmfctl simulate` (protocol/sim/channel_flags.h):
// "seminar 3 m=--rir bench/rirs/seminar_room_clap.wav --distance 3 --noise pink --noise-dbfs -50".
// Without --case, the table: the three measured rooms at 1 and 3 m; image-source
// rooms (6 x 8 x 3 m, a hard floor, the microphone 5 cm above it) tuned to RT60 0.3, 0.6,
// 1.0 and 1.5 s at 1, 3 and 5 m; clock offsets of +-2000 ppm, alone and in the seminar room;
// and a steady whine 6 dB over one of the profile's tones at six frequencies across the
// band. Pink noise at -50 dBFS everywhere. Each stream starts with `--lead-in-s` of the
// channel alone (a robot hears the room long before it is spoken to: whines are learnt).
// Scoring as the other sweeps (link/stream_trial.h). --json PATH writes the rows.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/channel_case.h"
#include "frames/sweep.h"
#include "frames/sweep_flags.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "sim/acoustic_channel.h"
#include "sim/channel_flags.h"
#include "sim/room_model.h"
#include "units/decibels.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr const char* kQuiet = " --noise pink --noise-dbfs -50";

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::vector<ChannelCase> default_cases(const LinkProfile& profile, const std::string& rirs) {
  std::vector<ChannelCase> cases;
  for (const char* room : kMeasuredRooms) {
    for (double d : {1.0, 3.0}) {
      cases.push_back({std::string(room) + " " + number(d) + " m",
                       "--rir " + rirs + "/" + room + ".wav --distance " + number(d) + kQuiet});
    }
  }
  for (double rt60 : {0.3, 0.6, 1.0, 1.5}) {
    for (double d : {1.0, 3.0, 5.0}) {
      cases.push_back({"image-source RT60 " + number(rt60) + " s " + number(d) + " m",
                       "--room 6x8x3 --room-rt60 " + number(rt60) + " --distance " + number(d) + kQuiet});
    }
  }
  for (double ppm : {2000.0, -2000.0})
    cases.push_back({"clock " + number(ppm) + " ppm", "--clock-ppm " + number(ppm) + kQuiet});
  cases.push_back(
      {"seminar_room_clap -2000 ppm", "--rir " + rirs + "/seminar_room_clap.wav --clock-ppm -2000" + kQuiet});
  // 6 dB over one tone as heard at 1 m: a tone of amplitude A is 20 log10(A / sqrt 2) dBFS RMS.
  const double whine_dbfs = units::db_from_amplitude_ratio(profile.tone_amplitude() / std::sqrt(2.0)) + 6;
  for (double hz : {5000.0, 6012.5, 9000.0, 12000.0, 15000.0, 16012.5}) {
    cases.push_back({"whine " + number(hz) + " Hz +6 dB", "--whine " + number(hz) + ":" + number(whine_dbfs) + kQuiet});
  }
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-rooms: frame success in measured and image-source rooms, with clock offsets and whines");
  std::string profile_name = "seed", json_path, rirs = "bench/rirs";
  std::vector<std::string> case_texts;
  SweepOptions options;
  options.threads = default_threads();
  options.topup_frames = 0;
  options.chunk_frames = 100;
  options.lead_in_s = 8;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--case", case_texts,
                 "NAME=FLAGS (dtmfctl simulate's channel flags); repeatable; default: the rooms table");
  app.add_option("--rirs", rirs, "where the measured rooms are")->capture_default_str();
  add_sweep_flags(app, options, "case", false);
  app.add_option("--lead-in-s", options.lead_in_s, "seconds of the channel alone before each stream's first frame")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        options.key = bench_key(authenticated);
        std::vector<ChannelCase> cases;
        for (const auto& t : case_texts) cases.push_back(parse_channel_case(t));
        if (cases.empty()) cases = default_cases(profile, rirs);

        // Each case's channel settings and its room, prepared once (a measured file read, a
        // shoebox tuned to its RT60) and shared by every stream.
        std::vector<sim::ChannelSetup> setups;
        std::vector<std::shared_ptr<const sim::RoomModel>> rooms;
        for (const ChannelCase& c : cases) {
          setups.push_back(channel_setup_of(c));
          const auto& room = setups.back().config.room;
          rooms.push_back(room.enabled() ? std::make_shared<const sim::RoomModel>(room, profile.sample_rate_hz)
                                         : nullptr);
        }
        std::printf("dtmf-bench-rooms: profile %s, seed %llu, %zu frames per case, %g s lead-in, %u threads\n",
                    profile.name.c_str(), static_cast<unsigned long long>(options.seed), options.frames,
                    options.lead_in_s, options.threads);
        std::fflush(stdout);

        std::vector<double> xs;
        for (std::size_t i = 0; i < cases.size(); ++i) xs.push_back(static_cast<double>(i));
        const auto started = std::chrono::steady_clock::now();
        const auto points = run_sweep(profile, xs, options, [&](double x, std::uint64_t seed) -> Channel {
          const auto i = static_cast<std::size_t>(x);
          sim::ChannelConfig config = setups[i].config;
          config.seed = seed;
          std::shared_ptr<sim::AcousticChannel> channel =
              rooms[i] ? std::make_shared<sim::AcousticChannel>(profile.sample_rate_hz, config, rooms[i])
                       : std::make_shared<sim::AcousticChannel>(profile.sample_rate_hz, config);
          if (setups[i].speaker_at)
            channel->add_transmitter_at(*setups[i].speaker_at);
          else
            channel->add_transmitter(setups[i].distance_m);
          return [channel](std::span<const float> clean, std::vector<float>& heard) { channel->process(clean, heard); };
        });
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;

        std::printf("%-36s %7s %9s %7s %6s %6s\n", "case", "frames", "success", "wrong", "twice", "NACKed");
        nlohmann::json rows = nlohmann::json::array();
        for (const auto& p : points) {
          const ChannelCase& c = cases[static_cast<std::size_t>(p.x)];
          const TrialCounts& n = p.counts;
          std::printf(
              "%-36s %7llu %8.2f%% %7llu %6llu %6llu\n", c.name.c_str(), static_cast<unsigned long long>(n.frames),
              100.0 * static_cast<double>(n.success) / static_cast<double>(std::max<std::uint64_t>(n.frames, 1)),
              static_cast<unsigned long long>(n.wrong_accepts), static_cast<unsigned long long>(n.duplicated),
              static_cast<unsigned long long>(n.check_failed));
          nlohmann::json row = point_json(p, "case_index");
          row["case"] = c.name;
          row["flags"] = c.flags;
          rows.push_back(row);
        }
        std::printf("%.1f s\n", took.count());
        write_json(json_path, {{"benchmark", "rooms"},
                               {"profile", profile.name},
                               {"authenticated", authenticated},
                               {"seed", options.seed},
                               {"frames_per_case", options.frames},
                               {"lead_in_s", options.lead_in_s},
                               {"threads", options.threads},
                               {"wall_s", took.count()},
                               {"cases", rows}});
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-rooms: %s\n", why.c_str()); });
}
