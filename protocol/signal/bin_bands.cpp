#include "signal/bin_bands.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "signal/spectrum.h"

namespace dtmf::signal {

namespace {
// Bins ordered as the readings rank them: by power, and among equal powers the lower index
// first. The bit pattern of a float >= 0 grows with its value, so one 64-bit key holds both
// (the power's bits, then the index counted down) and is unique for each bin: the best two
// are then the two largest keys, found with max and min alone, in any order of the bins.
// (Powers of a finite window are never negative or NaN.)
inline std::uint64_t rank_key(float power, int at) {
  std::uint32_t bits;
  std::memcpy(&bits, &power, sizeof bits);
  return (std::uint64_t{bits} << 32) | (0xFFFFFFFFu - static_cast<std::uint32_t>(at));
}
inline int key_index(std::uint64_t key) { return static_cast<int>(0xFFFFFFFFu - static_cast<std::uint32_t>(key)); }

struct TopTwo {
  std::uint64_t best = 0, second = 0;  // 0 is below every bin's key
  void add(std::uint64_t key) {
    second = std::max(second, std::min(best, key));
    best = std::max(best, key);
  }
  void add(const TopTwo& o) {
    second = std::max(std::max(second, o.second), std::min(best, o.best));
    best = std::max(best, o.best);
  }
};

// {index of the best, index of the runner-up} of v[0..n), n >= 2: the first index of the
// largest value, then the first index of the largest of the others.
inline std::pair<int, int> top_two(const float* v, int n) {
  TopTwo lanes[4];
  int t = 0;
  for (; t + 4 <= n; t += 4) {
    for (int l = 0; l < 4; ++l) lanes[l].add(rank_key(v[t + l], t + l));
  }
  for (; t < n; ++t) lanes[0].add(rank_key(v[t], t));
  lanes[0].add(lanes[1]);
  lanes[2].add(lanes[3]);
  lanes[0].add(lanes[2]);
  return {key_index(lanes[0].best), key_index(lanes[0].second)};
}
}  // namespace

BinBands::BinBands(int window_samples, std::span<const int> band_first_bin, int tones_per_band,
                   double presence_db, double dominance_db)
    : window_samples_(window_samples),
      first_bin_(band_first_bin.begin(), band_first_bin.end()),
      tones_(tones_per_band),
      presence_ratio_(static_cast<float>(std::pow(10.0, presence_db / 10.0))),
      dominance_ratio_(static_cast<float>(std::pow(10.0, dominance_db / 10.0))) {
  const int top_bin = window_samples / 2;
  if (tones_ < 3 || tones_ > 256) throw std::invalid_argument("a band needs 3 to 256 tones");
  for (const int first : first_bin_) {
    if (first < 1 || first + tones_ > top_bin) {
      throw std::invalid_argument("band at bin " + std::to_string(first) + " does not fit a " +
                                  std::to_string(window_samples) + "-sample window");
    }
  }
  powers_.assign(first_bin_.size() * static_cast<std::size_t>(tones_), 0.0f);
  readings_.resize(first_bin_.size());
  std::lock_guard lock(planner_mutex());
  input_ = fftwf_alloc_real(static_cast<std::size_t>(window_samples));
  output_ = fftwf_alloc_complex(static_cast<std::size_t>(top_bin + 1));
  // MEASURE: this size is planned once per process (FFTW keeps the wisdom) and runs
  // markedly faster than an estimated plan for a size that is not a power of two.
  // PRESERVE_INPUT is r2c's default, spelt out: analyze() runs the plan on the caller's window.
  plan_ = fftwf_plan_dft_r2c_1d(window_samples, input_, static_cast<fftwf_complex*>(output_),
                                FFTW_MEASURE | FFTW_PRESERVE_INPUT);
}

BinBands::~BinBands() {
  std::lock_guard lock(planner_mutex());
  fftwf_destroy_plan(plan_);
  fftwf_free(input_);
  fftwf_free(output_);
}

std::span<const BandReading> BinBands::analyze(std::span<const float> window, std::span<float> powers) {
  if (window.size() != static_cast<std::size_t>(window_samples_)) {
    throw std::invalid_argument("analysis window must hold " + std::to_string(window_samples_) + " samples");
  }
  if (powers.size() != powers_.size()) {
    throw std::invalid_argument("powers must hold " + std::to_string(powers_.size()) + " values");
  }
  // The plan preserves its input, so it reads the window where it lies when that is aligned
  // as its own input array was (SlidingWindow's windows are); otherwise, a copy.
  if (fftwf_alignment_of(const_cast<float*>(window.data())) == fftwf_alignment_of(input_)) {
    fftwf_execute_dft_r2c(plan_, const_cast<float*>(window.data()), static_cast<fftwf_complex*>(output_));
  } else {
    std::copy(window.begin(), window.end(), input_);
    fftwf_execute(plan_);
  }
  const auto* bins = static_cast<const fftwf_complex*>(output_);
  for (std::size_t band = 0; band < first_bin_.size(); ++band) {
    float* power = powers.data() + band * static_cast<std::size_t>(tones_);
    const fftwf_complex* x = bins + first_bin_[band];
    BandReading r;
    // Passes without data-dependent branches: the powers with their sum in four lanes, then
    // top_two() over keys (about half the time of the earlier maximum-then-scan, done twice;
    // one pass keeping a running best and second with branches took 1.1 us a window, nearly
    // the FFT's own time (bench/decoder)).
    float lanes[4] = {0, 0, 0, 0};
    int t = 0;
    for (; t + 4 <= tones_; t += 4) {
      for (int l = 0; l < 4; ++l) {
        power[t + l] = x[t + l][0] * x[t + l][0] + x[t + l][1] * x[t + l][1];
        lanes[l] += power[t + l];
      }
    }
    for (; t < tones_; ++t) {
      power[t] = x[t][0] * x[t][0] + x[t][1] * x[t][1];
      lanes[0] += power[t];
    }
    const float sum = (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
    const auto [best, second] = top_two(power, tones_);
    r.symbol = static_cast<std::uint8_t>(best);
    r.runner_up = static_cast<std::uint8_t>(second);
    r.best = power[best];
    r.second = power[second];
    r.floor = std::max(0.0f, sum - r.best - r.second) / static_cast<float>(tones_ - 2);
    r.present = r.best > presence_ratio_ * r.floor && r.best >= dominance_ratio_ * r.second && r.best > 0;
    readings_[band] = r;
  }
  return readings_;
}

}  // namespace dtmf::signal
