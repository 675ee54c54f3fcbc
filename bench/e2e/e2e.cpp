// dtmf-bench-e2e: the whole system in one process, commanded by a real gRPC client.
//
// tests/server/live_system.h puts the server's transmitter and the robot's agent in one
// process, talking through a simulated room that runs in real time (1 m, quiet white noise
// at -70 dBFS; or, with --rir, a measured room both ways in pink noise at -50 dBFS), with
// the gRPC service on a loopback port. This program sends `--commands`
// Drive commands (random speed and duration, seeded) one after another through a real
// client stub and measures, per command:
//   latency     from the RPC call until the FRAME_EVENT_CONFIRMED event reaches the client;
//   frames      first transmissions ACKed / first transmissions (frame success), and
//               retransmissions.
// Throughput: payload bits of the confirmed commands (every frame's data bits, check bits
// excluded: RESET, mode and parameter words, 3 x 12 = 36 bits per Drive in the seed profile;
// the 27-bit command payload of the one frame per command in the fast profile)
// divided by the wall time from the first call to the last confirmation.
// It runs in real time: about 3 s per command with the seed profile, 0.15 s with fast.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include <spdlog/spdlog.h>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "link/link.h"
#include "live_system.h"
#include "profile/link_profile.h"
#include "program_main.h"

using namespace dtmf;
using namespace dtmf::bench;
using Clock = std::chrono::steady_clock;

namespace {

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-e2e: command latency and throughput through the whole system (real time)");
  std::string profile_name = "seed", json_path;
  int commands = 20;
  std::uint64_t seed = 1;
  double distance_m = 1.0;
  std::string rir_file;
  double air_block_ms = 5;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--commands", commands, "Drive commands to send")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--distance-m", distance_m, "robot's distance from the sender")->capture_default_str();
  app.add_option("--rir", rir_file, "a measured room both ways (its impulse response file), pink noise at -50 dBFS");
  app.add_option("--air-block-ms", air_block_ms,
                 "the simulated room's audio period (as the round-trip benchmark: 5 ms, a low-latency device)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 50.0));
  app.add_option("--seed", seed, "random seed (speeds and durations)")->capture_default_str();
  bool no_listen_before_talk = false;
  app.add_flag("--no-listen-before-talk", no_listen_before_talk,
               "the sender does not listen before it talks (to measure what listening costs a robot alone)");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        const auto key = bench_key(authenticated);
        const auto link = link::make_link(profile);  // for payload sizes only
        spdlog::set_level(spdlog::level::warn);      // the agent's and server's per-frame lines would drown the summary
        test_support::LiveSystemOptions options;
        options.profile = &profile;
        options.distance_m = distance_m;
        options.air_block_ms = air_block_ms;
        options.rir_file = rir_file;
        options.default_policy = server::Policy::Fail;
        options.listen_before_talk = !no_listen_before_talk;
        options.sender_key = options.robot_key = key;
        test_support::LiveSystem system(options);
        spdlog::set_level(spdlog::level::warn);  // again: loggers made while starting take the global level
        auto client = system.client();
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> speed(0, 100), duration(0.5, 8);

        std::vector<double> latencies_ms, response_ms;
        nlohmann::json per_command = nlohmann::json::array();
        std::uint64_t confirmed = 0, payload_bits = 0, first_tx = 0, first_acked = 0, retransmissions = 0;
        const Clock::time_point first_call = Clock::now();
        Clock::time_point last_confirm = first_call;
        for (int i = 0; i < commands; ++i) {
          v1::DriveRequest request;
          request.set_speed_percent(std::round(speed(rng) * 10) / 10);
          request.set_duration_s(std::round(duration(rng) * 100) / 100);
          request.mutable_options()->set_profile(profile.name);
          grpc::ClientContext context;
          const Clock::time_point call = Clock::now();
          auto reader = client->Drive(&context, request);
          v1::DriveResponse response;
          std::optional<double> latency_ms;
          std::uint32_t frames = 0;
          std::vector<bool> acked_first;  // per frame: ACK on attempt 1
          while (reader->Read(&response)) {
            const v1::Progress& p = response.progress();
            frames = p.frame_count();
            if (acked_first.size() < frames) acked_first.resize(frames, false);
            if (p.event() == v1::FRAME_EVENT_TRANSMITTING && p.attempt() == 1) ++first_tx;
            if (p.event() == v1::FRAME_EVENT_RETRANSMITTING) ++retransmissions;
            if (p.event() == v1::FRAME_EVENT_ACK) {
              response_ms.push_back(p.response_time_ms());
              if (p.attempt() == 1 && p.frame_index() < frames) acked_first[p.frame_index()] = true;
            }
            if (p.event() == v1::FRAME_EVENT_CONFIRMED) {
              last_confirm = Clock::now();
              latency_ms = ms_between(call, last_confirm);
            }
          }
          const grpc::Status status = reader->Finish();
          first_acked += static_cast<std::uint64_t>(std::count(acked_first.begin(), acked_first.end(), true));
          if (latency_ms && status.ok()) {
            ++confirmed;
            // The command as sent: its payload bits whatever its frames (checks excluded).
            payload_bits += static_cast<std::uint64_t>(
                link->payload_bits(command::DriveForDuration{request.speed_percent(), request.duration_s()}));
            latencies_ms.push_back(*latency_ms);
          }
          per_command.push_back({{"speed_percent", request.speed_percent()},
                                 {"duration_s", request.duration_s()},
                                 {"frames", frames},
                                 {"confirmed", latency_ms.has_value() && status.ok()},
                                 {"latency_ms", latency_ms ? nlohmann::json(*latency_ms) : nlohmann::json(nullptr)},
                                 {"status", status.error_message()}});
          std::printf("command %2d/%d  drive %5.1f %% %4.2f s: %s%s\n", i + 1, commands, request.speed_percent(),
                      request.duration_s(), latency_ms ? "confirmed in " : "NOT confirmed ",
                      latency_ms ? (std::to_string(static_cast<int>(*latency_ms)) + " ms").c_str()
                                 : status.error_message().c_str());
          std::fflush(stdout);
        }
        const double wall_s = ms_between(first_call, last_confirm) / 1000;
        const double throughput = wall_s > 0 ? static_cast<double>(payload_bits) / wall_s : 0;
        const double frame_success = first_tx ? static_cast<double>(first_acked) / static_cast<double>(first_tx) : 0;
        // Alone in its room, the sender should never defer or yield: only its listening pauses.
        const server::AirShare air = system.air_share();
        std::printf(
            "e2e %s: %llu of %d commands confirmed; latency median %.0f ms, p95 %.0f ms, max %.0f ms; "
            "%.2f bit/s net payload; frames ACKed at the first attempt %llu of %llu (%.2f %%), %llu retransmissions; "
            "the air: %llu blocks heard busy, %llu answers of another's robot read under ours, %llu frames deferred, "
            "%llu yields, %llu listening pauses\n",
            profile.name.c_str(), static_cast<unsigned long long>(confirmed), commands, percentile(latencies_ms, 0.5),
            percentile(latencies_ms, 0.95), percentile(latencies_ms, 1.0), throughput,
            static_cast<unsigned long long>(first_acked), static_cast<unsigned long long>(first_tx),
            100 * frame_success, static_cast<unsigned long long>(retransmissions),
            static_cast<unsigned long long>(air.busy_blocks), static_cast<unsigned long long>(air.masked_answers),
            static_cast<unsigned long long>(air.deferred), static_cast<unsigned long long>(air.yields),
            static_cast<unsigned long long>(air.listens));
        write_json(json_path, {{"benchmark", "e2e"},
                               {"profile", profile.name},
                               {"authenticated", authenticated},
                               {"seed", seed},
                               {"distance_m", distance_m},
                               {"rir", rir_file},
                               {"commands", commands},
                               {"confirmed", confirmed},
                               {"latency_ms_median", percentile(latencies_ms, 0.5)},
                               {"latency_ms_p95", percentile(latencies_ms, 0.95)},
                               {"latency_ms_max", percentile(latencies_ms, 1.0)},
                               {"latencies_ms", latencies_ms},
                               {"response_times_ms", response_ms},
                               {"payload_bits", payload_bits},
                               {"wall_s", wall_s},
                               {"throughput_bps", throughput},
                               {"frames_first_attempt", first_tx},
                               {"frames_acked_first_attempt", first_acked},
                               {"frame_success_rate", frame_success},
                               {"retransmissions", retransmissions},
                               {"air_busy_blocks", air.busy_blocks},
                               {"air_masked_answers", air.masked_answers},
                               {"air_deferred", air.deferred},
                               {"air_yields", air.yields},
                               {"air_listens", air.listens},
                               {"per_command", per_command}});
        return confirmed == static_cast<std::uint64_t>(commands) ? 0 : 1;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-e2e: %s\n", why.c_str()); });
}
