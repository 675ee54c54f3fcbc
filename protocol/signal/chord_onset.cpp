#include "signal/chord_onset.h"

#include <algorithm>

namespace dtmf::signal {

std::optional<double> chord_steady_start(std::span<const float> amplitude, int window_samples, int hop_samples,
                                         float min_rise) {
  if (amplitude.size() < 2) return std::nullopt;
  const float floor = amplitude.front();
  const auto top = std::max_element(amplitude.begin(), amplitude.end());
  if (*top <= floor * min_rise) return std::nullopt;
  const float half = floor + 0.5f * (*top - floor);
  // The first window at or over half the plateau. Window 0, the floor, lies below half (the
  // plateau stands over it), so that window has one before it, below half.
  const auto k = static_cast<std::size_t>(
      std::find_if(amplitude.begin(), top + 1, [half](float a) { return a >= half; }) - amplitude.begin());
  const float below = amplitude[k - 1], above = amplitude[k];
  const double crossing_hops = static_cast<double>(k - 1) + (half - below) / (above - below);
  // That window holds half a window of the steady part: it began half a window before it.
  return crossing_hops * hop_samples + 0.5 * window_samples;
}

}  // namespace dtmf::signal
