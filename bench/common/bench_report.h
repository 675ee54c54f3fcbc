// What every benchmark program shares: writing its JSON file, a 95 % confidence interval
// for a rate, running independent jobs on a few threads, and the time it measured.
//
// Header-only. The JSON files are read by bench/write_benchmarks.py (docs/benchmarks.md);
// each carries the benchmark's name, the profile and the settings that produced it.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <exception>
#include <fstream>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace dtmf::bench {

// Writes `doc` to `path` (nothing for an empty path); throws when the file cannot be written.
inline void write_json(const std::string& path, const nlohmann::json& doc) {
  if (path.empty()) return;
  std::ofstream out(path);
  out << doc.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

// Wilson score interval (95 %) for `k` successes in `n` trials: {low, high}, as fractions.
// Unlike k/n +- ..., it stays inside [0, 1] and means something at 0 or n of n.
inline std::pair<double, double> wilson95(std::uint64_t k, std::uint64_t n) {
  if (n == 0) return {0.0, 1.0};
  const double z = 1.959964, nn = static_cast<double>(n), p = static_cast<double>(k) / nn;
  const double centre = (p + z * z / (2 * nn)) / (1 + z * z / nn);
  const double half = z * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn)) / (1 + z * z / nn);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

// Now, as a benchmark's JSON names when it measured: "2026-11-29 14:26 UTC".
inline std::string utc_now_text() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

// The p-quantile (0..1) of `v`, interpolated between the two nearest ranks; 0 when empty.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double at = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (at - static_cast<double>(lo));
}

// Runs job(0) .. job(count - 1) on `threads` threads, each job once; jobs must be independent.
// The first exception a job throws is rethrown here once every thread has stopped.
inline void run_parallel(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::exception_ptr failure;
  auto worker = [&] {
    for (std::size_t i; (i = next++) < count;) {
      try {
        job(i);
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::max(1u, threads); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

inline unsigned default_threads() { return std::max(1u, std::min(2u, std::thread::hardware_concurrency())); }

}  // namespace dtmf::bench
