#include "sim/room_decay.h"

#include <algorithm>
#include <cmath>

#include "units/decibels.h"

namespace dtmf::sim {

namespace {
constexpr double kT20StartDb = -5.0;
constexpr double kT20EndDb = -25.0;
}  // namespace

std::vector<double> energy_decay_curve_db(std::span<const float> response) {
  std::vector<double> edc(response.size());
  double remaining = 0;
  for (std::size_t i = response.size(); i-- > 0;) {
    remaining += static_cast<double>(response[i]) * response[i];
    edc[i] = remaining;
  }
  const double total = response.empty() ? 0 : edc[0];
  for (double& e : edc) e = total > 0 && e > 0 ? units::db_from_power_ratio(e / total) : -400.0;
  return edc;
}

std::optional<double> rt60_t20_s(std::span<const float> response, int sample_rate_hz) {
  const auto edc = energy_decay_curve_db(response);
  const auto start = std::find_if(edc.begin(), edc.end(), [](double e) { return e <= kT20StartDb; });
  const auto end = std::find_if(start, edc.end(), [](double e) { return e <= kT20EndDb; });
  if (end == edc.end() || end - start < 2) return std::nullopt;
  // Least-squares line through (t, EDC) between the two points.
  double n = 0, st = 0, se = 0, stt = 0, ste = 0;
  for (auto it = start; it != end; ++it) {
    const double t = static_cast<double>(it - edc.begin()) / sample_rate_hz;
    n += 1;
    st += t;
    se += *it;
    stt += t * t;
    ste += t * *it;
  }
  const double slope_db_per_s = (n * ste - st * se) / (n * stt - st * st);
  if (!(slope_db_per_s < 0)) return std::nullopt;
  return -60.0 / slope_db_per_s;
}

std::array<std::optional<double>, kOctaveBands> band_rt60_t20_s(std::span<const float> response, int sample_rate_hz) {
  std::array<std::optional<double>, kOctaveBands> out;
  for (std::size_t b = 0; b < kOctaveBands; ++b) {
    // A band above Nyquist has no content to measure.
    if (kOctaveCentresHz[b] >= sample_rate_hz / 2.0) continue;
    out[b] = rt60_t20_s(band_filtered(response, b, sample_rate_hz), sample_rate_hz);
  }
  return out;
}

std::size_t decay_point(std::span<const float> response, double drop_db) {
  const auto edc = energy_decay_curve_db(response);
  const auto it = std::find_if(edc.begin(), edc.end(), [&](double e) { return e <= -drop_db; });
  return static_cast<std::size_t>(it - edc.begin());
}

double direct_to_reverberant_db(std::span<const float> response, int sample_rate_hz, double direct_window_s) {
  if (response.empty()) return 0;
  std::size_t peak = 0;
  for (std::size_t i = 0; i < response.size(); ++i) {
    if (std::abs(response[i]) > std::abs(response[peak])) peak = i;
  }
  const auto window = static_cast<std::size_t>(direct_window_s * sample_rate_hz);
  double direct = 0, reverberant = 0;
  for (std::size_t i = peak >= window ? peak - window : 0; i < response.size(); ++i) {
    const double e = static_cast<double>(response[i]) * response[i];
    (i <= peak + window ? direct : reverberant) += e;
  }
  return reverberant > 0 ? units::db_from_power_ratio(direct / reverberant) : 400.0;
}

}  // namespace dtmf::sim
