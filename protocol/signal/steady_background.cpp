#include "signal/steady_background.h"
#include "units/decibels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dtmf::signal {

SteadyBackground::SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor)
    : enabled_(rise_db_per_s > 0),
      rise_per_window_(static_cast<float>(units::amplitude_ratio_from_db(rise_db_per_s / windows_per_s))),
      floor_(floor),
      background_(bins, floor),
      excess_(bins, 0.0f) {
  if (rise_db_per_s < 0 || windows_per_s <= 0) {
    throw std::invalid_argument(
        "a steady background needs a rise of 0 dB/s or more and windows per second over 0, got " +
        std::to_string(rise_db_per_s) + " dB/s and " + std::to_string(windows_per_s));
  }
}

void SteadyBackground::reset() { std::fill(background_.begin(), background_.end(), floor_); }

std::span<const float> SteadyBackground::remove(std::span<const float> magnitudes) {
  if (!enabled_) return magnitudes;
  const std::size_t n = std::min(magnitudes.size(), background_.size());
  for (std::size_t k = 0; k < n; ++k) {
    const float m = magnitudes[k];
    float& b = background_[k];
    b = std::min(m, std::max(b, floor_) * rise_per_window_);
    excess_[k] = std::sqrt(std::max(0.0f, m * m - b * b));
  }
  return std::span<const float>(excess_.data(), n);
}

}  // namespace dtmf::signal
