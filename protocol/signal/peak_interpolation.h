// Signal layer: a spectral peak to a fraction of a bin, from the peak bin's magnitude and its
// two neighbours'. One estimator per analysis window, each matched to its window's main lobe:
//
//   Hann (the seed's spectrum): a parabola through the three log magnitudes, which puts a
//     clean tone within about 1 Hz of its frequency; the offset is clamped to ±0.5 bin, and
//     the level to the window's scalloping loss (+1.42 dB), because a neighbour near zero
//     (a bin wholly taken off as steady background) throws the parabola.
//   rectangular (the fast profile's frames): the larger neighbour's share of the magnitude,
//     a / (a0 + a): a rectangular window's lobe is a sinc, for which this ratio is the
//     tone's distance from the bin's centre.
// Header-only, pure arithmetic.
#pragma once

#include <algorithm>
#include <cmath>

namespace dtmf::signal {

struct InterpolatedPeak {
  double offset_bins;  // -0.5 .. 0.5 from the peak bin
  double magnitude;    // the tone's magnitude, the window's scalloping loss made good
};

inline constexpr double kHannScallopingGain = 1.178;  // +1.42 dB: a Hann window's worst-case loss

// `left`, `centre`, `right`: magnitudes, centre the largest (a local maximum).
inline InterpolatedPeak hann_peak(float left, float centre, float right) {
  const double a = std::log(std::max(left, 1e-20f));
  const double b = std::log(centre);
  const double c = std::log(std::max(right, 1e-20f));
  const double denominator = a - 2 * b + c;
  const double delta = denominator < 0 ? std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5) : 0.0;
  const double level =
      std::min(std::exp(b - 0.25 * (a - c) * delta), static_cast<double>(centre) * kHannScallopingGain);
  return {delta, level};
}

// Magnitudes of a rectangular window's bins; the offset from the centre bin in bins.
inline float rectangular_peak_offset(float left, float centre, float right) {
  return right > left ? right / (centre + right + 1e-30f) : -left / (centre + left + 1e-30f);
}

}  // namespace dtmf::signal
