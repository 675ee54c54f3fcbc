// dtmf-bench-watch: what watching the air costs the sender, and how soon a watcher sees it.
//
// The in-process system of the server tests (tests/server/live_system.h), its sender driving a
// fast command every half second throughout. Phases alternate, each --seconds long: nobody
// watches, then one watcher (this program with --be-watcher, a process of its own, so that
// its reading costs the sender nothing) watches the air with the full spectrum (50 columns a
// second of 512 bins, the cap). Figures:
//   extra_cpu_pct_core  the process's CPU over the watched phases less over the unwatched
//                       ones, in % of one core (the robot's agent and the simulated room run
//                       in this process too, alike in both phases);
//   latency_ms          from a frame's chord start (its FramePlayed time) to the watcher
//                       reading it, on this machine's one wall clock: median, 95th, max;
//   columns_per_s, dropped_columns, dropped_events   what the watcher got and lost.
// Target (issue 60): extra CPU <= 2 % of a core; latency median <= 100 ms.
#include <spawn.h>
#include <sys/wait.h>

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/bench_report.h"
#include "live_system.h"
#include "program_main.h"

extern char** environ;

using namespace dtmf;
using namespace std::chrono_literals;

namespace {

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

std::int64_t now_unix_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

// --be-watcher: watches the air on `port` for `seconds` at the full spectrum; writes what it saw to `out`.
int be_watcher(int port, double seconds, const std::string& out) {
  auto stub = v1::TeleopService::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(static_cast<int>(seconds * 1000)));
  v1::WatchAirRequest request;
  request.set_spectrum(true);
  request.set_columns_per_s(50);
  request.set_bins(512);
  const auto began = std::chrono::steady_clock::now();
  auto reader = stub->WatchAir(&context, request);
  v1::WatchAirResponse m;
  nlohmann::json doc{{"latency_ms", nlohmann::json::array()},
                     {"columns", 0},
                     {"dropped_columns", 0},
                     {"dropped_events", 0},
                     {"frames", 0}};
  while (reader->Read(&m)) {
    doc["dropped_columns"] = doc["dropped_columns"].get<std::uint64_t>() + m.dropped_columns();
    doc["dropped_events"] = doc["dropped_events"].get<std::uint64_t>() + m.dropped_events();
    if (m.has_spectrum()) doc["columns"] = doc["columns"].get<int>() + 1;
    if (m.has_frame_played()) {
      doc["frames"] = doc["frames"].get<int>() + 1;
      doc["latency_ms"].push_back(static_cast<double>(now_unix_ms() - m.time_unix_ms()));
    }
  }
  reader->Finish();
  doc["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::ofstream(out) << doc.dump();
  return 0;
}

// Starts this program as the watcher; its pid.
pid_t start_watcher(const char* self, int port, double seconds, const std::string& out) {
  std::vector<std::string> args = {
      self, "--be-watcher", std::to_string(port), "--seconds", std::to_string(seconds), "--watcher-out", out};
  std::vector<char*> argp;
  for (auto& a : args) argp.push_back(a.data());
  argp.push_back(nullptr);
  pid_t child = 0;
  if (posix_spawn(&child, self, nullptr, nullptr, argp.data(), environ) != 0)
    throw std::runtime_error("cannot start the watcher process (" + std::string(self) + ")");
  return child;
}

// Drives a fast command every half second until `stop`; counts what was confirmed.
void drive(test_support::LiveSystem& system, const std::atomic<bool>& stop, std::atomic<int>& confirmed) {
  auto client = system.client();
  for (int i = 0; !stop; ++i) {
    const auto next = std::chrono::steady_clock::now() + 500ms;
    v1::DriveRequest r;
    r.set_speed_percent(10 + i % 50);
    r.set_duration_s(1);
    r.mutable_options()->set_profile("fast");
    const auto result =
        test_support::read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, r); });
    if (result.status.ok()) ++confirmed;
    std::this_thread::sleep_until(next);  // the pace of the load is the benchmark's setting
  }
}

int run_bench(const char* self, double seconds, int phases, const std::string& json_path) {
  spdlog::set_level(spdlog::level::warn);
  test_support::LiveSystem system;
  std::atomic<bool> stop{false};
  std::atomic<int> confirmed{0};
  std::thread load([&] { drive(system, stop, confirmed); });
  double idle_cpu_s = 0, watched_cpu_s = 0;
  std::vector<double> latencies;
  std::uint64_t columns = 0, dropped_columns = 0, dropped_events = 0;
  double watched_s = 0;  // the watcher's own time
  const std::string out =
      (std::filesystem::temp_directory_path() / ("dtmf-bench-watch-" + std::to_string(::getpid()) + ".json")).string();
  for (int p = 0; p < phases; ++p) {
    double before = process_cpu_s();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));  // the unwatched phase
    idle_cpu_s += process_cpu_s() - before;
    const pid_t watcher = start_watcher(self, system.port(), seconds + 1, out);
    const auto given_up = std::chrono::steady_clock::now() + 10s;
    while (system.air_watchers() == 0) {
      if (std::chrono::steady_clock::now() > given_up) throw std::runtime_error("the watcher never began to watch");
      std::this_thread::sleep_for(10ms);  // a process starting: nothing to be told by
    }
    before = process_cpu_s();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));  // the watched phase
    watched_cpu_s += process_cpu_s() - before;
    ::waitpid(watcher, nullptr, 0);
    std::ifstream in(out);
    const auto seen = nlohmann::json::parse(in);
    for (double l : seen["latency_ms"]) latencies.push_back(l);
    columns += seen["columns"].get<std::uint64_t>();
    watched_s += seen["seconds"].get<double>();
    dropped_columns += seen["dropped_columns"].get<std::uint64_t>();
    dropped_events += seen["dropped_events"].get<std::uint64_t>();
  }
  stop = true;
  load.join();
  const double span_s = seconds * phases;
  const nlohmann::json doc{{"benchmark", "watch"},
                           {"seconds_per_phase", seconds},
                           {"phases", phases},
                           {"commands_confirmed", confirmed.load()},
                           {"cpu_unwatched_pct_core", 100 * idle_cpu_s / span_s},
                           {"cpu_watched_pct_core", 100 * watched_cpu_s / span_s},
                           {"extra_cpu_pct_core", 100 * (watched_cpu_s - idle_cpu_s) / span_s},
                           {"latency_ms",
                            {{"count", latencies.size()},
                             {"median", percentile(latencies, 0.5)},
                             {"p95", percentile(latencies, 0.95)},
                             {"max", latencies.empty() ? 0.0 : *std::max_element(latencies.begin(), latencies.end())}}},
                           {"columns_per_s", static_cast<double>(columns) / watched_s},
                           {"dropped_columns", dropped_columns},
                           {"dropped_events", dropped_events}};
  std::printf(
      "watching the air: %+.2f %% of a core (%.1f %% unwatched, %.1f %% watched); frame to watcher: median "
      "%.0f ms, p95 %.0f ms (%zu frames); %.1f columns/s, %llu columns and %llu events dropped\n",
      doc["extra_cpu_pct_core"].get<double>(), doc["cpu_unwatched_pct_core"].get<double>(),
      doc["cpu_watched_pct_core"].get<double>(), percentile(latencies, 0.5), percentile(latencies, 0.95),
      latencies.size(), doc["columns_per_s"].get<double>(), static_cast<unsigned long long>(dropped_columns),
      static_cast<unsigned long long>(dropped_events));
  bench::write_json(json_path, doc);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-watch: what watching the air (WatchAir, full spectrum) costs the sender, and its latency");
  double seconds = 10;
  int phases = 3, watcher_port = 0;
  std::string json_path, watcher_out;
  app.add_option("--seconds", seconds, "each phase's length")->check(CLI::PositiveNumber);
  app.add_option("--phases", phases, "unwatched and watched phases, alternating")->check(CLI::PositiveNumber);
  app.add_option("--json", json_path, "write the figures here");
  app.add_option("--be-watcher", watcher_port, "internal: be the watcher, of the server on this port");
  app.add_option("--watcher-out", watcher_out, "internal: where the watcher writes what it saw");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  if (watcher_port > 0) return be_watcher(watcher_port, seconds, watcher_out);
  return program::run([&] { return run_bench(argv[0], seconds, phases, json_path); },
                      [](const std::string& error) { std::fprintf(stderr, "dtmf-bench-watch: %s\n", error.c_str()); });
}
