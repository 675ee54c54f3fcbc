#include "signal/peak_detector.h"
#include "units/decibels.h"

#include <algorithm>
#include <cmath>

namespace dtmf::signal {

namespace {
constexpr double kHannScallopingGain = 1.178;  // +1.42 dB: a Hann window's worst-case loss, made good
}  // namespace

double dbfs(double amplitude) { return units::db_from_amplitude_ratio(std::max(amplitude, 1e-12)); }
double amplitude_from_dbfs(double level_dbfs) { return units::amplitude_ratio_from_db(level_dbfs); }

PeakDetector::PeakDetector(const DetectorParams& params, double bin_hz, std::size_t bin_count)
    : bin_hz_(bin_hz),
      gate_(static_cast<float>(amplitude_from_dbfs(params.noise_gate_dbfs))),
      peak_count_(static_cast<std::size_t>(params.peak_count)) {
  first_bin_ = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(params.bandpass_low_hz / bin_hz)));
  last_bin_ =
      std::min<std::size_t>(bin_count - 2, static_cast<std::size_t>(std::floor(params.bandpass_high_hz / bin_hz)));
  candidates_.reserve(last_bin_ > first_bin_ ? (last_bin_ - first_bin_) / 2 + 1 : 1);
}

std::span<const Peak> PeakDetector::detect(std::span<const float> m) {
  candidates_.clear();
  for (std::size_t k = first_bin_; k <= last_bin_; ++k) {
    if (m[k] < gate_ || m[k] <= m[k - 1] || m[k] < m[k + 1]) continue;
    const double a = std::log(std::max(m[k - 1], 1e-20f));
    const double b = std::log(m[k]);
    const double c = std::log(std::max(m[k + 1], 1e-20f));
    const double denominator = a - 2 * b + c;
    // Both clamped to what a Hann window can do: a tone lies within half a bin of its
    // peak bin and reads at most 1.42 dB low there (its scalloping loss). Without the
    // clamp, a neighbour near zero (a bin wholly taken off as steady background) threw
    // the parabola and read a -25 dBFS peak as -3 dBFS.
    const double delta = denominator < 0 ? std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5) : 0.0;
    const double level =
        std::min(std::exp(b - 0.25 * (a - c) * delta), static_cast<double>(m[k]) * kHannScallopingGain);
    candidates_.push_back(Peak{(static_cast<double>(k) + delta) * bin_hz_, level});
  }
  const std::size_t keep = std::min(peak_count_, candidates_.size());
  std::partial_sort(candidates_.begin(), candidates_.begin() + static_cast<std::ptrdiff_t>(keep), candidates_.end(),
                    [](const Peak& x, const Peak& y) { return x.amplitude > y.amplitude; });
  return std::span<const Peak>(candidates_.data(), keep);
}

}  // namespace dtmf::signal
