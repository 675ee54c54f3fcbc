#include "signal/peak_detector.h"

#include <algorithm>
#include <cmath>

#include "signal/peak_interpolation.h"
#include "units/decibels.h"

namespace dtmf::signal {

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
    // Clamped to what a Hann window can do (peak_interpolation.h): without the clamp, a
    // neighbour near zero threw the parabola and read a -25 dBFS peak as -3 dBFS.
    const InterpolatedPeak peak = hann_peak(m[k - 1], m[k], m[k + 1]);
    candidates_.push_back(Peak{(static_cast<double>(k) + peak.offset_bins) * bin_hz_, peak.magnitude});
  }
  const std::size_t keep = std::min(peak_count_, candidates_.size());
  std::partial_sort(candidates_.begin(), candidates_.begin() + static_cast<std::ptrdiff_t>(keep), candidates_.end(),
                    [](const Peak& x, const Peak& y) { return x.amplitude > y.amplitude; });
  return std::span<const Peak>(candidates_.data(), keep);
}

}  // namespace dtmf::signal
