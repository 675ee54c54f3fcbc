#include "sim/radial_motion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/acoustic_channel.h"
#include "sim/kaiser.h"
#include "sim/number_text.h"

namespace dtmf::sim {

namespace {

constexpr int kTaps = 2 * kMovingDelayHalfTaps;
constexpr int kPhases = 512;  // table resolution; linear interpolation between phases
constexpr double kKaiserBeta = 9.0;
constexpr double kMaxSpeedMps = 50;

// table[phase][j]: the weight of x[i - K + 1 + j] for a read position i + phase / kPhases.
const std::vector<std::array<float, kTaps>>& sinc_table() {
  static const auto table = [] {
    std::vector<std::array<float, kTaps>> t(kPhases + 1);
    for (int p = 0; p <= kPhases; ++p) {
      const double frac = static_cast<double>(p) / kPhases;
      double sum = 0;
      for (int j = 0; j < kTaps; ++j) {
        const double x = frac - (j - kMovingDelayHalfTaps + 1);  // distance from tap to position
        const double sinc = x == 0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
        const double r = x / kMovingDelayHalfTaps;
        const double window = kaiser(r, kKaiserBeta);
        t[static_cast<std::size_t>(p)][static_cast<std::size_t>(j)] = static_cast<float>(sinc * window);
        sum += sinc * window;
      }
      // Unit gain at 0 Hz for every phase: no level ripple as the delay slides.
      for (float& c : t[static_cast<std::size_t>(p)]) c = static_cast<float>(c / sum);
    }
    return t;
  }();
  return table;
}

}  // namespace

MovingDelay::MovingDelay(const RadialMotion& motion, double start_distance_m, double offset_samples, int sample_rate_hz)
    : motion_(motion), start_m_(start_distance_m), offset_samples_(offset_samples), sample_rate_hz_(sample_rate_hz) {
  if (!(motion.min_distance_m > 0) || !(motion.max_distance_m > motion.min_distance_m) ||
      !std::isfinite(motion.max_distance_m)) {
    throw std::invalid_argument("radial motion range " + number_text(motion.min_distance_m) + " .. " +
                                number_text(motion.max_distance_m) + " m: give 0 < min < max");
  }
  if (!(start_distance_m >= motion.min_distance_m && start_distance_m <= motion.max_distance_m)) {
    throw std::invalid_argument("a moving transmitter starts at " + number_text(start_distance_m) +
                                " m, outside its range " + number_text(motion.min_distance_m) + " .. " +
                                number_text(motion.max_distance_m) + " m: widen the range");
  }
  if (!std::isfinite(motion.speed_mps) || std::abs(motion.speed_mps) > kMaxSpeedMps) {
    throw std::invalid_argument("radial speed " + number_text(motion.speed_mps) +
                                " m/s: give a speed within +-50 m/s (a robot drives at about 0.2 m/s)");
  }
  sinc_table();
}

double MovingDelay::distance_m(double t_s) const {
  // A triangle wave: travelled distance folded back and forth between min and max.
  const double span = motion_.max_distance_m - motion_.min_distance_m;
  double u = std::fmod(start_m_ - motion_.min_distance_m + motion_.speed_mps * t_s, 2 * span);
  if (u < 0) u += 2 * span;
  return motion_.min_distance_m + (u <= span ? u : 2 * span - u);
}

void MovingDelay::process(std::span<const float> in, std::span<float> out) {
  history_.insert(history_.end(), in.begin(), in.end());
  const auto& table = sinc_table();
  const double samples_per_m = sample_rate_hz_ / kSpeedOfSoundMps;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const long long n = produced_ + static_cast<long long>(i);
    // The distance when this sample is heard: offset_samples later, after the fixed delay
    // that follows this line (it was 0.7 samples off at 2 m/s when taken at n).
    const double d = distance_m((static_cast<double>(n) + offset_samples_) / sample_rate_hz_);
    const double delay = std::max<double>(d * samples_per_m - offset_samples_, kMovingDelayHalfTaps);
    const double position = static_cast<double>(n) - delay;  // stream index to read at
    const double whole = std::floor(position);
    const double phase = (position - whole) * kPhases;
    const auto p = static_cast<std::size_t>(phase);
    const float mix = static_cast<float>(phase - static_cast<double>(p));
    const long long first = static_cast<long long>(whole) - kMovingDelayHalfTaps + 1 - base_;
    float acc = 0;
    for (int j = 0; j < kTaps; ++j) {
      const long long k = first + j;
      const float x = k >= 0 ? history_[static_cast<std::size_t>(k)] : 0.0f;  // before the stream: silence
      const std::size_t jj = static_cast<std::size_t>(j);
      acc += x * (table[p][jj] + mix * (table[p + 1][jj] - table[p][jj]));
    }
    out[i] = static_cast<float>(acc * start_m_ / d);
  }
  produced_ += static_cast<long long>(out.size());
  // Keep what the earliest future read can still need (the longest delay plus the taps).
  const double longest = motion_.max_distance_m * samples_per_m - offset_samples_ + kTaps + 2;
  const long long keep_from = produced_ - static_cast<long long>(std::ceil(longest));
  if (keep_from - base_ > (1 << 15)) {
    history_.erase(history_.begin(), history_.begin() + static_cast<std::ptrdiff_t>(keep_from - base_));
    base_ = keep_from;
  }
}

}  // namespace dtmf::sim
