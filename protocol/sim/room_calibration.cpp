#include "sim/room_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/number_text.h"
#include "sim/room_decay.h"

namespace dtmf::sim {

namespace {

constexpr double kMinRt60S = 0.1;
constexpr double kTolerance = 0.02;
constexpr int kMaxTries = 16;
// Absorption exponent a = -ln(r): from r = 0.9999 (a nearly lossless wall) to r = 0.001.
constexpr double kMinExponent = 1e-4, kMaxExponent = 6.9;

ShoeboxRoom with_walls(ShoeboxRoom room, double r) {
  for (Surface s : {kWallX0, kWallX1, kWallY0, kWallY1, kCeiling}) room.reflection[s] = uniform_bands(r);
  return room;
}

double mean_band(const BandValues& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

}  // namespace

double eyring_rt60_s(const ShoeboxRoom& room) {
  const double lx = room.size_m.x, ly = room.size_m.y, lz = room.size_m.z;
  const double areas[kSurfaces] = {ly * lz, ly * lz, lx * lz, lx * lz, lx * ly, lx * ly};
  double total = 0, absorbed = 0;
  for (std::size_t s = 0; s < kSurfaces; ++s) {
    const double r = mean_band(room.reflection[s]);
    total += areas[s];
    absorbed += areas[s] * (1 - r * r);
  }
  const double mean_absorption = std::min(absorbed / total, 0.999999);
  return 0.161 * lx * ly * lz / (-total * std::log(1 - mean_absorption));
}

CalibratedRoom calibrate_rt60(const ShoeboxRoom& room, const Point3& speaker, const Point3& mic, double rt60_s,
                              int sample_rate_hz, std::uint64_t seed) {
  check_room(room);
  if (!std::isfinite(rt60_s) || rt60_s < kMinRt60S || rt60_s > room.max_length_s) {
    throw std::invalid_argument("RT60 " + number_text(rt60_s) + " s: give 0.1 s to " + number_text(room.max_length_s) +
                                " s (the longest response generated)");
  }
  // T20 ends at -25 dB, 0.42 RT60 into an exponential decay: 0.75 RT60 leaves room for a
  // slower one, and what is cut off (-45 dB) bends the curve by less than 0.05 dB there.
  const double length_s = std::min(room.max_length_s, distance_m(speaker, mic) / 343.0 + 0.05 + 0.75 * rt60_s);
  // Eyring's guess for uniform walls: RT60 = 0.161 V / (2 a S), so a = 0.161 V / (2 S RT60).
  const double lx = room.size_m.x, ly = room.size_m.y, lz = room.size_m.z;
  const double surface = 2 * (lx * ly + lx * lz + ly * lz);
  double a = std::clamp(0.161 * lx * ly * lz / (2 * surface * rt60_s), kMinExponent, kMaxExponent);
  double low = kMinExponent, high = kMaxExponent;  // the answer lies between (RT60 falls as a grows)
  CalibratedRoom best;
  double best_error = 1e300;
  int tries = 0;
  while (tries < kMaxTries) {
    ++tries;
    const ShoeboxRoom trial = with_walls(room, std::exp(-a));
    const auto h = image_source_response(trial, speaker, mic, sample_rate_hz, seed, length_s);
    const auto measured = rt60_t20_s(h, sample_rate_hz);
    // No 25 dB fall within the response: far too reverberant.
    const double reached = measured.value_or(10 * rt60_s);
    const double error = std::abs(reached / rt60_s - 1);
    if (error < best_error) {
      best_error = error;
      best = {trial, std::exp(-a), reached, 0};
    }
    if (error <= kTolerance) break;
    if (reached > rt60_s)
      low = a;
    else
      high = a;
    double next = a * std::min(reached / rt60_s, 4.0);
    if (!(next > low && next < high)) next = std::sqrt(low * high);  // overshot: bisect the bracket
    if (high / low < 1.0005) break;
    a = next;
  }
  best.tries = tries;
  if (best_error > 0.1) {
    throw std::invalid_argument("a " + number_text(lx) + " x " + number_text(ly) + " x " + number_text(lz) +
                                " m room with this floor cannot reach RT60 " + number_text(rt60_s) +
                                " s: the closest was " + number_text(best.rt60_s) + " s with walls at " +
                                number_text(best.reflection) + "; change the room's size or the floor's reflection");
  }
  return best;
}

}  // namespace dtmf::sim
