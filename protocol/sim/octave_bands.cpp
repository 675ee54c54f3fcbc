#include "sim/octave_bands.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/real_fft.h"

namespace dtmf::sim {

double band_weight(std::size_t band, double frequency_hz) {
  const double lowest = kOctaveCentresHz.front(), highest = kOctaveCentresHz.back();
  // Position on the log2 axis, in octaves above the lowest centre, clamped to the bank.
  const double octave = std::clamp(std::log2(std::max(frequency_hz, 1e-9) / lowest), 0.0, std::log2(highest / lowest));
  const double distance = std::abs(octave - static_cast<double>(band));
  // Flat to a third of an octave from the centre, then a cos^2 crossover centred on the band
  // edge (half an octave out), where the neighbour takes over with the matching sin^2.
  const double start = 0.5 - kCrossoverOctaves / 2;
  if (distance <= start) return 1.0;
  if (distance >= 0.5 + kCrossoverOctaves / 2) return 0.0;
  const double c = std::cos(0.5 * std::numbers::pi * (distance - start) / kCrossoverOctaves);
  return c * c;
}

double band_analysis_weight(std::size_t band, double frequency_hz) {
  const double octave = std::log2(std::max(frequency_hz, 1e-9) / kOctaveCentresHz.front());
  const double distance = std::abs(octave - static_cast<double>(band));
  constexpr double kFlat = 1.0 / 6, kEdge = 1.0 / 4;
  if (distance <= kFlat) return 1.0;
  if (distance >= kEdge) return 0.0;
  const double c = std::cos(0.5 * std::numbers::pi * (distance - kFlat) / (kEdge - kFlat));
  return c * c;
}

BandValues bands_from_points(std::span<const std::pair<double, double>> points) {
  if (points.empty()) throw std::invalid_argument("no values given for the octave bands");
  std::vector<std::pair<double, double>> sorted(points.begin(), points.end());
  std::sort(sorted.begin(), sorted.end());
  BandValues out;
  for (std::size_t b = 0; b < kOctaveBands; ++b) {
    const double f = kOctaveCentresHz[b];
    if (f <= sorted.front().first) {
      out[b] = sorted.front().second;
    } else if (f >= sorted.back().first) {
      out[b] = sorted.back().second;
    } else {
      const auto above = std::upper_bound(sorted.begin(), sorted.end(), std::make_pair(f, -1e300));
      const auto below = above - 1;
      const double t = std::log(f / below->first) / std::log(above->first / below->first);
      out[b] = below->second + t * (above->second - below->second);
    }
  }
  return out;
}

std::vector<float> band_filtered(std::span<const float> signal, std::size_t band, int sample_rate_hz) {
  if (band >= kOctaveBands) throw std::invalid_argument("no octave band " + std::to_string(band));
  // Padding: the zero-phase filter's pre-ringing (tens of ms at 125 Hz) wraps into it.
  const std::size_t pad = static_cast<std::size_t>(sample_rate_hz / 10);
  const RealFft fft(fft_size_at_least(signal.size() + pad));
  FftReal x(fft.size(), 0.0f);
  std::copy(signal.begin(), signal.end(), x.begin());
  FftBins bins(fft.bins());
  fft.forward(x.data(), bins.data());
  for (std::size_t k = 0; k < bins.size(); ++k) {
    const double f = static_cast<double>(k) * sample_rate_hz / static_cast<double>(fft.size());
    bins[k] *= static_cast<float>(band_analysis_weight(band, f) / static_cast<double>(fft.size()));
  }
  fft.inverse(bins.data(), x.data());
  return std::vector<float>(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(signal.size()));
}

std::string band_name(std::size_t band) {
  const double f = kOctaveCentresHz.at(band);
  return f >= 1000 ? std::to_string(static_cast<int>(f / 1000)) + " kHz" : std::to_string(static_cast<int>(f)) + " Hz";
}

}  // namespace dtmf::sim
