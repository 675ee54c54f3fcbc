#include "signal/spectrum_columns.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtmf::signal {

SpectrumColumns::SpectrumColumns(int sample_rate_hz, double low_hz, double high_hz, int bins, double columns_per_s)
    : sample_rate_hz_(sample_rate_hz),
      low_hz_(low_hz),
      step_hz_((high_hz - low_hz) / std::max(bins, 1)),
      bins_(bins),
      hop_samples_(static_cast<int>(std::lround(sample_rate_hz / std::max(columns_per_s, 1e-3)))),
      analyzer_(kFftSamples, sample_rate_hz),
      history_(kFftSamples, 0.0f),
      window_(kFftSamples, 0.0f) {
  if (bins < 1 || !(low_hz >= 0 && high_hz > low_hz && high_hz <= sample_rate_hz / 2.0) || hop_samples_ < 1)
    throw std::invalid_argument("spectrum columns need 0 <= low_hz < high_hz <= half the sample rate, a bin, a rate");
}

std::vector<ColumnLevels> SpectrumColumns::feed(std::span<const float> samples) {
  std::vector<ColumnLevels> due;
  for (const float s : samples) {
    // A ring would save the copy; at 50 columns a second the copy is 100 k floats a second.
    history_[fed_ % kFftSamples] = s;
    ++fed_;
    if (++since_column_ < static_cast<std::size_t>(hop_samples_)) continue;
    since_column_ = 0;
    due.push_back(column());
  }
  return due;
}

ColumnLevels SpectrumColumns::column() {
  // The ring, oldest sample first.
  const std::size_t start = fed_ % kFftSamples;
  std::copy(history_.begin() + static_cast<std::ptrdiff_t>(start), history_.end(), window_.begin());
  std::copy(history_.begin(), history_.begin() + static_cast<std::ptrdiff_t>(start),
            window_.begin() + static_cast<std::ptrdiff_t>(kFftSamples - start));
  const std::span<const float> amplitude = analyzer_.analyze(window_);
  ColumnLevels c{1000.0 * static_cast<double>(fed_) / sample_rate_hz_,
                 std::vector<float>(static_cast<std::size_t>(bins_), kFloorDbfs)};
  const double bin_hz = analyzer_.bin_hz();
  for (int b = 0; b < bins_; ++b) {
    const double from_hz = low_hz_ + b * step_hz_;
    // Every FFT bin whose centre lies in [from, from + step), and at least the nearest one.
    const auto first = static_cast<std::size_t>(std::ceil(from_hz / bin_hz));
    const auto last = std::max(first, static_cast<std::size_t>(std::ceil((from_hz + step_hz_) / bin_hz)) - 1);
    float loudest = 0;
    for (std::size_t k = first; k <= last && k < amplitude.size(); ++k) loudest = std::max(loudest, amplitude[k]);
    if (loudest > 0) c.level_dbfs[static_cast<std::size_t>(b)] = std::max(kFloorDbfs, 20.0f * std::log10(loudest));
  }
  return c;
}

}  // namespace dtmf::signal
