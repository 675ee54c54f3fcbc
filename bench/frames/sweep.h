// A frame-success sweep: many continuous streams per point, run on a few threads, topped up
// where the result sits near a threshold.
//
// Each point (an SNR, a distance) first gets `frames` frames, as streams of `chunk_frames`
// (independent seeds, so they can run in parallel); a point whose success rate then lies in
// [topup_low, topup_high), or is the first point past such a one, gets more streams until it
// has `topup_frames`: the points on the slope and just above it, where the lowest SNR
// reaching 99 % or 99.9 % is decided, get the most trials.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frames/stream_trial.h"

namespace dtmf::bench {

struct SweepOptions {
  std::size_t frames = 1000;
  std::size_t topup_frames = 10000;
  double topup_low = 0.90;
  double topup_high = 0.9999;
  std::size_t chunk_frames = 500;
  std::size_t block_samples = 1024;
  std::uint64_t seed = 1;
  unsigned threads = 2;
  double lead_in_s = 0;  // channel only, before each stream's first frame (StreamOptions)
  // Authenticated frames under this key (none: unauthenticated): FrameTrials.
  std::shared_ptr<const security::LinkKey> key;
};

// The channel of one stream at point value `x`, its noise seeded with `seed`.
using ChannelFactory = std::function<Channel(double x, std::uint64_t seed)>;

struct SweepPoint {
  double x;
  TrialCounts counts;
  double seconds = 0;  // wall time spent on the point's streams (summed over threads)
};

std::vector<SweepPoint> run_sweep(const LinkProfile& profile, const std::vector<double>& xs,
                                  const SweepOptions& options, const ChannelFactory& channel);

// One point as JSON: counts, rates and their 95 % intervals.
nlohmann::json point_json(const SweepPoint& point, const std::string& x_name);

// The lowest x from which every point up to the best end reaches `rate` (points sorted by
// x; `increasing`: better with larger x, as SNR; else better with smaller x, as distance).
// Null when not even the best point reaches it.
nlohmann::json threshold(const std::vector<SweepPoint>& points, double rate, bool increasing);

// A table on stdout: x, frames, success %, wrong accepts, check failures.
void print_points(const std::vector<SweepPoint>& points, const std::string& x_label);

}  // namespace dtmf::bench
