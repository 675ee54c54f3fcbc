#include "frames/sweep.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "common/bench_report.h"

namespace dtmf::bench {

namespace {

std::uint64_t mix(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t z = seed ^ (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^ (c * 0x165667B19E3779F9ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

struct Job {
  std::size_t point;
  std::size_t chunk;  // index among the point's streams, so seeds never repeat
  std::size_t frames;
};

double rate(std::uint64_t k, std::uint64_t n) { return n == 0 ? 0.0 : static_cast<double>(k) / static_cast<double>(n); }

}  // namespace

std::vector<SweepPoint> run_sweep(const LinkProfile& profile, const std::vector<double>& xs,
                                  const SweepOptions& options, const ChannelFactory& channel) {
  std::vector<SweepPoint> points;
  for (double x : xs) points.push_back({x, {}, 0});
  std::vector<std::size_t> chunks_used(xs.size(), 0);
  std::mutex mutex;

  auto schedule = [&](std::size_t point, std::size_t frames, std::vector<Job>& jobs) {
    while (frames > 0) {
      const std::size_t n = std::min(frames, options.chunk_frames);
      jobs.push_back({point, chunks_used[point]++, n});
      frames -= n;
    }
  };
  auto run = [&](const std::vector<Job>& jobs) {
    run_parallel(jobs.size(), options.threads, [&](std::size_t i) {
      const Job& job = jobs[i];
      const auto started = std::chrono::steady_clock::now();
      FrameTrials trials(profile, options.key);
      StreamOptions stream{job.frames, mix(options.seed, job.point, job.chunk, 1), options.block_samples};
      stream.lead_in_slots = static_cast<std::size_t>(
          std::ceil(options.lead_in_s * profile.sample_rate_hz / static_cast<double>(trials.slot_samples())));
      const TrialCounts counts =
          run_stream(trials, stream, channel(points[job.point].x, mix(options.seed, job.point, job.chunk, 2)));
      const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
      std::lock_guard lock(mutex);
      points[job.point].counts += counts;
      points[job.point].seconds += took.count();
    });
  };

  std::vector<Job> jobs;
  for (std::size_t p = 0; p < points.size(); ++p) schedule(p, options.frames, jobs);
  run(jobs);
  jobs.clear();
  // On the slope, and the first point above it: 1000 of 1000 cannot tell 99.9 % from 100 %.
  auto on_slope = [&](std::size_t p) {
    const double success = rate(points[p].counts.success, points[p].counts.frames);
    return success >= options.topup_low && success < options.topup_high;
  };
  for (std::size_t p = 0; p < points.size(); ++p) {
    const TrialCounts& c = points[p].counts;
    const bool above_slope = p > 0 && on_slope(p - 1) && rate(c.success, c.frames) >= options.topup_high;
    if ((on_slope(p) || above_slope) && c.frames < options.topup_frames)
      schedule(p, options.topup_frames - c.frames, jobs);
  }
  run(jobs);
  return points;
}

nlohmann::json point_json(const SweepPoint& point, const std::string& x_name) {
  const TrialCounts& c = point.counts;
  const auto [s_low, s_high] = wilson95(c.success, c.frames);
  const auto [w_low, w_high] = wilson95(c.wrong_accepts, c.frames);
  return {{x_name, point.x},
          {"frames", c.frames},
          {"success", c.success},
          {"missed", c.missed},
          {"duplicated", c.duplicated},
          {"wrong_accepts", c.wrong_accepts},
          {"check_failed", c.check_failed},
          {"success_rate", rate(c.success, c.frames)},
          {"success_rate_ci95", {s_low, s_high}},
          {"wrong_accept_rate", rate(c.wrong_accepts, c.frames)},
          {"wrong_accept_rate_ci95", {w_low, w_high}},
          {"seconds", point.seconds}};
}

nlohmann::json threshold(const std::vector<SweepPoint>& points, double wanted, bool increasing) {
  nlohmann::json best = nullptr;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const SweepPoint& p = points[increasing ? n - 1 - i : i];
    if (rate(p.counts.success, p.counts.frames) < wanted) break;
    best = p.x;
  }
  return best;
}

void print_points(const std::vector<SweepPoint>& points, const std::string& x_label) {
  std::printf("%10s %8s %10s %9s %9s %12s %10s\n", x_label.c_str(), "frames", "success", "missed", "dupl.",
              "wrong acc.", "check fail");
  for (const SweepPoint& p : points) {
    const TrialCounts& c = p.counts;
    std::printf("%10g %8llu %9.3f%% %9llu %9llu %12llu %10llu\n", p.x, static_cast<unsigned long long>(c.frames),
                100.0 * rate(c.success, c.frames), static_cast<unsigned long long>(c.missed),
                static_cast<unsigned long long>(c.duplicated), static_cast<unsigned long long>(c.wrong_accepts),
                static_cast<unsigned long long>(c.check_failed));
  }
}

}  // namespace dtmf::bench
