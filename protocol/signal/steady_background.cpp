#include "signal/steady_background.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "units/decibels.h"

namespace dtmf::signal {

SteadyBackground::SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor)
    : SteadyBackground(bins, rise_db_per_s, windows_per_s, floor * floor, floor * floor) {}

SteadyBackground SteadyBackground::for_power(std::size_t bins, double rise_db_per_s, double windows_per_s) {
  // Starting at the largest float, the first window's power becomes the background at once.
  return SteadyBackground(bins, rise_db_per_s, windows_per_s, 0.0f, std::numeric_limits<float>::max());
}

SteadyBackground::SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor_power,
                                   float start_power)
    : enabled_(rise_db_per_s > 0),
      rise_per_window_(static_cast<float>(units::power_ratio_from_db(rise_db_per_s / windows_per_s))),
      floor_power_(floor_power),
      start_power_(start_power),
      background_(bins, start_power),
      excess_(bins, 0.0f) {
  if (rise_db_per_s < 0 || windows_per_s <= 0) {
    throw std::invalid_argument(
        "a steady background needs a rise of 0 dB/s or more and windows per second over 0, got " +
        std::to_string(rise_db_per_s) + " dB/s and " + std::to_string(windows_per_s));
  }
}

void SteadyBackground::reset() { std::fill(background_.begin(), background_.end(), start_power_); }

float SteadyBackground::learn(std::size_t bin, float power) {
  float& b = background_[bin];
  b = std::min(power, std::max(b, floor_power_) * rise_per_window_);
  return b;
}

std::span<const float> SteadyBackground::remove(std::span<const float> magnitudes) {
  if (!enabled_) return magnitudes;
  const std::size_t n = std::min(magnitudes.size(), background_.size());
  for (std::size_t k = 0; k < n; ++k) {
    const float power = magnitudes[k] * magnitudes[k];
    excess_[k] = std::sqrt(std::max(0.0f, power - learn(k, power)));
  }
  return std::span<const float>(excess_.data(), n);
}

void SteadyBackground::remove_power(std::span<const float> powers, std::span<float> excess) {
  const std::size_t n = std::min({powers.size(), excess.size(), background_.size()});
  for (std::size_t k = 0; k < n; ++k) excess[k] = enabled_ ? powers[k] - learn(k, powers[k]) : powers[k];
}

}  // namespace dtmf::signal
