// dtmf-bench-room-stop: the stop for every robot (docs/protocol.md §10, "A stop for every
// robot"), heard by three robots in one room: the Fleet section's broadcast-stop target of
// docs/benchmarks.md.
//
// A stream of `--stops` stops, one per `--slot-ms`, each the profile's broadcast copies back to
// back as the sender plays them (with keys: sealed under the room key, each copy its own
// room counter). Three robots, at 1, 2 and 3 m from the sender's loudspeaker, each with its
// own key and the room key, hear the stream through the room at their own distance (a
// channel each, its own noise); pink noise at -50 dBFS. A robot counts a stop when its
// receiver executes one of the stop's copies (a Command, Stop{every_robot}) within
// `--within-ms` of the first copy's start, as the agent acts on it the moment it decides.
// Printed per room: the share of stops all three robots executed in time, each robot's
// share, the decision time after the first copy's start (median, 95th percentile, most), and
// stops executed twice (both copies: harmless) or not at all. Also counted: anything a robot
// executed that was not a stop for every robot (must be 0), and answers (must be 0).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <future>
#include <memory>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/channel_case.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "security/counter_file.h"
#include "sim/acoustic_channel.h"
#include "sim/channel_flags.h"
#include "sim/room_model.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr std::array<double, 3> kRobotDistanceM = {1.0, 2.0, 3.0};
constexpr double kLeadInS = 1;  // the robots hear the room before the first stop

struct RobotCounts {
  std::uint64_t in_time = 0, late = 0, missed = 0, twice = 0, other = 0, answered = 0;
  std::vector<double> decision_ms;  // first execution after the first copy's start
};

std::shared_ptr<const security::LinkKey> test_key(unsigned char seed) {
  std::array<unsigned char, security::kKeyBytes> bytes{};
  bytes.fill(seed);
  return security::LinkKey::from_bytes(bytes);
}

struct CaseResult {
  std::string room;
  std::uint64_t stops = 0, all_in_time = 0;
  std::array<RobotCounts, 3> robots;
};

CaseResult run_case(const LinkProfile& profile, const ChannelCase& room_case, bool keyed, std::size_t stops,
                    double slot_ms, double within_ms, std::uint64_t seed) {
  const sim::ChannelSetup setup = channel_setup_of(room_case);
  const auto room = setup.config.room.enabled()
                        ? std::make_shared<const sim::RoomModel>(setup.config.room, profile.sample_rate_hz)
                        : nullptr;
  const auto room_key = keyed ? test_key(0x99) : nullptr;
  link::LinkOptions sender_options;
  sender_options.key = room_key;
  // Room counters name times (security/room_freshness.h): start at today's clock.
  sender_options.counters =
      std::make_shared<security::MemoryCounterStore>(security::clock_counter_floor(std::chrono::system_clock::now()));
  const auto sender = link::make_link(profile, sender_options);
  const double samples_per_ms = profile.sample_rate_hz / 1000.0;
  const auto slot = static_cast<std::size_t>(slot_ms * samples_per_ms);
  const auto lead = static_cast<std::size_t>(kLeadInS * 1000 * samples_per_ms);
  std::vector<float> track(lead + stops * slot + slot, 0.0f);
  std::vector<double> first_copy_ms;
  for (std::size_t k = 0; k < stops; ++k) {
    std::size_t at = lead + k * slot;
    first_copy_ms.push_back(static_cast<double>(at) / samples_per_ms);
    for (const link::TransmitFrame& f : sender->plan(command::Stop{true})) {
      std::copy(f.audio.begin(), f.audio.end(), track.begin() + static_cast<long>(at));
      at += static_cast<std::size_t>(f.next_frame_after_ms * samples_per_ms);
    }
  }
  CaseResult result{room_case.name, stops, 0, {}};
  std::vector<std::vector<double>> executed(3);  // per robot, per stop: first execution (ms after the first copy)
  std::vector<std::future<void>> robots;
  for (std::size_t r = 0; r < 3; ++r) {
    robots.push_back(std::async(std::launch::async, [&, r] {
      link::LinkOptions o;
      o.address = static_cast<std::uint8_t>(r + 1);
      if (keyed) {
        o.key = test_key(static_cast<unsigned char>(r + 1));
        o.room_key = room_key;
      }
      const auto robot = link::make_link(profile, o);
      sim::ChannelConfig config = setup.config;
      config.seed = seed + r;
      auto channel = room ? std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config, room)
                          : std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config);
      channel->add_transmitter(kRobotDistanceM[r]);
      std::vector<float> heard;
      const std::array<std::span<const float>, 1> in{std::span<const float>(track)};
      channel->process(in, heard);
      RobotCounts& n = result.robots[r];
      std::vector<int> times(stops, 0);
      std::vector<double> first(stops, -1);
      const auto receiver = robot->receiver();
      const auto block = static_cast<std::size_t>(robot->receiver_block_samples());
      for (std::size_t at = 0; at + block <= heard.size(); at += block) {
        for (const link::Reception& rec : receiver->feed(std::span<const float>(heard).subspan(at, block))) {
          if (!robot->answer_audio(rec).empty()) ++n.answered;
          if (!rec.command) continue;
          if (!command::every_robot(*rec.command)) {
            ++n.other;
            continue;
          }
          const double slot_at =
              (rec.heard_ms * samples_per_ms - static_cast<double>(lead)) / static_cast<double>(slot);
          if (slot_at < 0 || slot_at >= static_cast<double>(stops)) continue;
          const auto k = static_cast<std::size_t>(slot_at);
          if (times[k]++ == 0) first[k] = rec.heard_ms - first_copy_ms[k];
        }
      }
      for (std::size_t k = 0; k < stops; ++k) {
        if (times[k] == 0) {
          ++n.missed;
          continue;
        }
        n.twice += times[k] >= 2 ? 1 : 0;
        n.decision_ms.push_back(first[k]);
        ++(first[k] <= within_ms ? n.in_time : n.late);
      }
      executed[r] = first;
    }));
  }
  for (auto& f : robots) f.get();
  for (std::size_t k = 0; k < stops; ++k) {
    bool all = true;
    for (std::size_t r = 0; r < 3; ++r) all = all && executed[r][k] >= 0 && executed[r][k] <= within_ms;
    result.all_in_time += all ? 1 : 0;
  }
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dtmf-bench-room-stop: the stop for every robot, heard by three robots in each measured room"};
  std::string profile_name = "fast", json_path, rirs = "bench/rirs";
  std::vector<std::string> rooms;
  std::size_t stops = 1000;
  double slot_ms = 1000, within_ms = 300, noise_dbfs = -50;
  std::uint64_t seed = 1;
  bool authenticated = false;
  app.add_option("--profile", profile_name, "link profile (one whose frames name robots)")->capture_default_str();
  add_authenticated_flag(app, authenticated);
  app.add_option("--rirs", rirs, "the measured rooms' directory")->capture_default_str();
  app.add_option("--room", rooms, "room files' stems (default: every measured room)");
  app.add_option("--stops", stops, "stops per room")->check(CLI::Range(1, 1000000))->capture_default_str();
  app.add_option("--slot-ms", slot_ms, "one stop per slot")->check(CLI::Range(400.0, 10000.0))->capture_default_str();
  app.add_option("--within-ms", within_ms, "the target: executed within this of the first copy's start")
      ->capture_default_str();
  app.add_option("--noise-dbfs", noise_dbfs, "the pink noise at each robot's microphone")->capture_default_str();
  app.add_option("--seed", seed, "the channels' noise")->capture_default_str();
  app.add_option("--json", json_path, "also write the results as JSON");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        if (rooms.empty()) rooms.assign(std::begin(kMeasuredRooms), std::end(kMeasuredRooms));
        nlohmann::json out = {{"profile", profile.name},
                              {"authenticated", authenticated},
                              {"stops", stops},
                              {"within_ms", within_ms},
                              {"cases", nlohmann::json::array()}};
        out["noise_dbfs"] = noise_dbfs;
        out["measured_utc"] = utc_now_text();
        std::printf("%-22s %9s %9s %9s %9s %8s %8s %8s %6s %6s\n", "room", "all 3", "robot 1m", "robot 2m", "robot 3m",
                    "median", "p95", "most", "other", "answ");
        for (const std::string& room : rooms) {
          const ChannelCase c{
              room, "--rir " + rirs + "/" + room + ".wav --noise pink --noise-dbfs " + std::to_string(noise_dbfs)};
          const CaseResult r = run_case(profile, c, authenticated, stops, slot_ms, within_ms, seed);
          std::vector<double> all_ms;
          std::uint64_t other = 0, answered = 0;
          nlohmann::json robots = nlohmann::json::array();
          for (std::size_t i = 0; i < 3; ++i) {
            const RobotCounts& n = r.robots[i];
            all_ms.insert(all_ms.end(), n.decision_ms.begin(), n.decision_ms.end());
            other += n.other;
            answered += n.answered;
            robots.push_back({{"distance_m", kRobotDistanceM[i]},
                              {"in_time", n.in_time},
                              {"late", n.late},
                              {"missed", n.missed},
                              {"twice", n.twice}});
          }
          const auto pct = [&](std::uint64_t k) {
            return 100.0 * static_cast<double>(k) / static_cast<double>(r.stops);
          };
          std::printf("%-22s %8.2f%% %8.2f%% %8.2f%% %8.2f%% %6.0fms %6.0fms %6.0fms %6llu %6llu\n", room.c_str(),
                      pct(r.all_in_time), pct(r.robots[0].in_time), pct(r.robots[1].in_time), pct(r.robots[2].in_time),
                      percentile(all_ms, 0.5), percentile(all_ms, 0.95), percentile(all_ms, 1.0),
                      static_cast<unsigned long long>(other), static_cast<unsigned long long>(answered));
          nlohmann::json entry = {{"room", room}, {"all_in_time", r.all_in_time}, {"robots", robots}};
          entry["all_in_time_pct"] = pct(r.all_in_time);
          entry["decision_median_ms"] = percentile(all_ms, 0.5);
          entry["decision_p95_ms"] = percentile(all_ms, 0.95);
          entry["decision_max_ms"] = percentile(all_ms, 1.0);
          entry["other_commands"] = other;
          entry["answered"] = answered;
          out["cases"].push_back(entry);
        }
        if (!json_path.empty()) write_json(json_path, out);
        return 0;
      },
      [](const std::string& what) { std::fprintf(stderr, "dtmf-bench-room-stop: %s\n", what.c_str()); });
}
