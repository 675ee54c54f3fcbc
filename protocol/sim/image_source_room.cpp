#include "sim/image_source_room.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "sim/acoustic_channel.h"
#include "sim/kaiser.h"
#include "sim/number_text.h"
#include "sim/real_fft.h"
#include "sim/room_decay.h"
#include "units/decibels.h"

namespace dtmf::sim {

namespace {

constexpr std::size_t B = kOctaveBands;
constexpr int kSincHalfTaps = 32;
constexpr double kSincKaiserBeta = 8.0;
constexpr double kLengthMarginFactor = 1.2;  // on the slowest axial decay, an upper bound
constexpr double kFadeOutS = 0.005;
// An image whose amplitude (relative to a direct sound at 1 m) is below this is left out:
// even ten million of them add up to less than -90 dB. Most late images of an absorbing
// room are far below it (0.9^300), which is what keeps long responses quick to make.
constexpr double kNegligibleGain = 1e-8;

using Gains = std::array<float, B>;

// One image coordinate on one axis: where it lies relative to the microphone, what its
// walls do to each band, how many walls it met.
struct AxisImage {
  double offset_m;
  Gains gain;
  int order;
  std::uint64_t key;    // (n, q): identifies the image for its random displacement
  float loudest_after;  // the largest band gain of this image and every farther one
};

std::vector<AxisImage> axis_images(double side_m, double source, double mic, const BandValues& wall0,
                                   const BandValues& wall1, double reach_m) {
  std::vector<AxisImage> out;
  const int n_max = static_cast<int>(std::ceil((reach_m + side_m) / (2 * side_m))) + 1;
  for (int n = -n_max; n <= n_max; ++n) {
    for (int q = 0; q <= 1; ++q) {
      // Allen and Berkley: the image at 2 n L + (1 - 2q) s met the wall at 0 |n - q| times
      // and the wall at L |n| times.
      const double offset = 2.0 * n * side_m + (1 - 2 * q) * source - mic;
      if (std::abs(offset) > reach_m) continue;
      const int at0 = std::abs(n - q), at1 = std::abs(n);
      AxisImage image{offset, {}, at0 + at1, static_cast<std::uint64_t>((n + 100000) * 2 + q), 0.0f};
      for (std::size_t b = 0; b < B; ++b) {
        image.gain[b] = static_cast<float>(std::pow(wall0[b], at0) * std::pow(wall1[b], at1));
      }
      out.push_back(image);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const AxisImage& a, const AxisImage& b) { return std::abs(a.offset_m) < std::abs(b.offset_m); });
  float loudest = 0;
  for (auto it = out.rbegin(); it != out.rend(); ++it) {
    loudest = std::max(loudest, *std::max_element(it->gain.begin(), it->gain.end()));
    it->loudest_after = loudest;
  }
  return out;
}

std::uint64_t mix(std::uint64_t z) {  // splitmix64's finaliser
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Three uniform numbers in [-1, 1) from 63 random bits, 21 each.
std::array<double, 3> uniform3_pm1(std::uint64_t bits) {
  constexpr double kScale = 0x1.0p-20;
  return {static_cast<double>(bits & 0x1fffff) * kScale - 1.0,
          static_cast<double>((bits >> 21) & 0x1fffff) * kScale - 1.0,
          static_cast<double>((bits >> 42) & 0x1fffff) * kScale - 1.0};
}

// How long the response needs: the slowest axial decay (a sound bouncing between two
// facing surfaces, the last to die in a shoebox) to -60 dB, air absorption left out.
double estimated_length_s(const ShoeboxRoom& room, double direct_s) {
  const double sides[3] = {room.size_m.x, room.size_m.y, room.size_m.z};
  double slowest_s = 0;
  for (int axis = 0; axis < 3; ++axis) {
    double r0 = 0, r1 = 0;
    for (std::size_t b = 0; b < B; ++b) {
      r0 = std::max(r0, room.reflection[static_cast<std::size_t>(2 * axis)][b]);
      r1 = std::max(r1, room.reflection[static_cast<std::size_t>(2 * axis + 1)][b]);
    }
    if (r0 * r1 <= 0) continue;
    const double db_per_s = -units::db_from_amplitude_ratio(r0 * r1) * kSpeedOfSoundMps / (2 * sides[axis]);
    slowest_s = std::max(slowest_s, 60.0 / db_per_s);
  }
  const double diagonal_m = std::sqrt(sides[0] * sides[0] + sides[1] * sides[1] + sides[2] * sides[2]);
  return direct_s + 2 * diagonal_m / kSpeedOfSoundMps + kLengthMarginFactor * slowest_s;
}

// Air absorption by arrival time, per band, 10^(-alpha(f) * d / 20), in steps of
// kAirStep samples (5 cm at 48 kHz: 0.02 dB at 16 kHz), small enough to stay in cache.
constexpr std::size_t kAirStep = 8;
std::vector<Gains> air_gains(const ShoeboxRoom& room, std::size_t length, double fs) {
  std::vector<Gains> air(length / kAirStep + 2);
  for (std::size_t i = 0; i < air.size(); ++i) {
    const double d = static_cast<double>(i * kAirStep) / fs * kSpeedOfSoundMps;
    for (std::size_t b = 0; b < B; ++b) {
      const double f = kOctaveCentresHz[b];
      air[i][b] = room.air_absorption
                      ? static_cast<float>(units::amplitude_ratio_from_db(-kAirAbsorptionDbPerMPerHz2 * f * f * d))
                      : 1.0f;
    }
  }
  return air;
}

// One image's sound, `g` per band, arriving `t` samples in: a band-limited impulse at the exact
// time (a Kaiser-windowed sinc) while `fractional`, else at the nearest sample.
void add_arrival(std::vector<float>& trains, std::size_t length, double t, const Gains& g, bool fractional) {
  if (!fractional) {
    float* row = trains.data() + static_cast<std::size_t>(std::lround(t)) * B;
    for (std::size_t b = 0; b < B; ++b) row[b] += g[b];
    return;
  }
  const auto whole = static_cast<long long>(std::floor(t));
  for (long long k = whole - kSincHalfTaps + 1; k <= whole + kSincHalfTaps; ++k) {
    if (k < 0 || k >= static_cast<long long>(length)) continue;
    const double x = static_cast<double>(k) - t;
    const double r = x / kSincHalfTaps;
    if (std::abs(r) >= 1) continue;
    const double sinc = x == 0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
    const double w = sinc * kaiser(r, kSincKaiserBeta);
    float* row = trains.data() + static_cast<std::size_t>(k) * B;
    for (std::size_t b = 0; b < B; ++b) row[b] += static_cast<float>(w) * g[b];
  }
}

// The images along each axis, and how far and how long their sound is followed.
struct Images {
  std::vector<AxisImage> xs, ys, zs;
  std::size_t length;
  double fs, reach_m, direct_s;
};

// Each band's impulse train of every image within reach, [sample][band]: float halves the
// cache misses.
std::vector<float> image_trains(const ShoeboxRoom& room, const Images& images, std::uint64_t seed) {
  const std::size_t length = images.length;
  const double fs = images.fs;
  const std::vector<Gains> air = air_gains(room, length, fs);
  std::vector<float> trains(length * B, 0.0f);  // [sample][band]: float halves the cache misses
  const double fractional_until = images.direct_s * fs + kFractionalDelayS * fs;
  const double jitter_m = room.randomization_m;
  const double reach2 = images.reach_m * images.reach_m;

  for (const AxisImage& ix : images.xs) {
    const double x2 = ix.offset_m * ix.offset_m;
    // Beyond reach, or so many reflections on the way that nothing farther can matter.
    if (x2 > reach2 || ix.loudest_after < kNegligibleGain * std::abs(ix.offset_m)) break;
    const float gx_max = *std::max_element(ix.gain.begin(), ix.gain.end());
    for (const AxisImage& iy : images.ys) {
      const double xy2 = x2 + iy.offset_m * iy.offset_m;
      if (xy2 > reach2 || gx_max * iy.loudest_after < kNegligibleGain * std::sqrt(xy2)) break;
      Gains gxy;
      for (std::size_t b = 0; b < B; ++b) gxy[b] = ix.gain[b] * iy.gain[b];
      const float gxy_max = *std::max_element(gxy.begin(), gxy.end());
      for (const AxisImage& iz : images.zs) {
        const double d2 = xy2 + iz.offset_m * iz.offset_m;
        double d = std::sqrt(d2);
        if (d2 > reach2 || gxy_max * iz.loudest_after < kNegligibleGain * d) break;
        if (jitter_m > 0 && ix.order + iy.order + iz.order >= 2) {
          const auto u = uniform3_pm1(mix(mix(mix(seed ^ ix.key) ^ iy.key) ^ iz.key));
          const double dx = ix.offset_m + jitter_m * u[0];
          const double dy = iy.offset_m + jitter_m * u[1];
          const double dz = iz.offset_m + jitter_m * u[2];
          d = std::sqrt(dx * dx + dy * dy + dz * dz);
        }
        const double t = d / kSpeedOfSoundMps * fs;
        if (t >= static_cast<double>(length) - 1) continue;
        const auto nearest = static_cast<std::size_t>(std::lround(t));
        const float spread = static_cast<float>(1.0 / std::max(d, kMinInsideM));
        Gains g;
        const Gains& absorbed = air[(nearest + kAirStep / 2) / kAirStep];
        for (std::size_t b = 0; b < B; ++b) g[b] = gxy[b] * iz.gain[b] * spread * absorbed[b];
        add_arrival(trains, length, t, g, t < fractional_until);
      }
    }
  }
  return trains;
}

std::vector<float> band_filtered_sum(const std::vector<float>& trains, std::size_t length, double fs) {
  // Each band's train through its band filter, summed in the frequency domain.
  const std::size_t pad = static_cast<std::size_t>(fs / 10);  // the band filters' pre-ringing wraps into it
  const RealFft fft(fft_size_at_least(length + pad));
  FftReal x(fft.size(), 0.0f);
  FftBins band(fft.bins()), sum(fft.bins(), {0.0f, 0.0f});
  for (std::size_t b = 0; b < B; ++b) {
    if (kOctaveCentresHz[b] / 2 >= fs / 2) continue;  // a band wholly above Nyquist
    for (std::size_t n = 0; n < length; ++n) x[n] = trains[n * B + b];
    fft.forward(x.data(), band.data());
    for (std::size_t k = 0; k < band.size(); ++k) {
      const double f = static_cast<double>(k) * fs / static_cast<double>(fft.size());
      sum[k] += band[k] * static_cast<float>(band_weight(b, f) / static_cast<double>(fft.size()));
    }
  }
  fft.inverse(sum.data(), x.data());
  return {x.begin(), x.begin() + static_cast<std::ptrdiff_t>(length)};
}

// An automatic length: cut where the response has decayed by 60 dB, and fade the cut out.
void trim_to_decay(std::vector<float>& h, double direct_s, double fs) {
  const std::size_t end = std::max(decay_point(h, 60.0), static_cast<std::size_t>((direct_s + kFractionalDelayS) * fs));
  if (end < h.size()) h.resize(end);
  const auto fade = std::min(h.size() / 4, static_cast<std::size_t>(kFadeOutS * fs));
  for (std::size_t i = 0; i < fade; ++i) {
    h[h.size() - fade + i] *= static_cast<float>(
        0.5 + 0.5 * std::cos(std::numbers::pi * static_cast<double>(i + 1) / static_cast<double>(fade + 1)));
  }
}

}  // namespace

std::vector<float> image_source_response(const ShoeboxRoom& room, const Point3& speaker_in, const Point3& mic_in,
                                         int sample_rate_hz, std::uint64_t seed, double length_s) {
  check_room(room);
  check_inside(room, speaker_in, "the loudspeaker");
  check_inside(room, mic_in, "the microphone");
  if (distance_m(speaker_in, mic_in) < kMinInsideM) {
    throw std::invalid_argument("the loudspeaker and the microphone are less than 1 cm apart: move one of them");
  }
  // Reciprocity, exactly: the same pair in either order makes the same images.
  const bool swap = std::tie(speaker_in.x, speaker_in.y, speaker_in.z) > std::tie(mic_in.x, mic_in.y, mic_in.z);
  const Point3 speaker = swap ? mic_in : speaker_in, mic = swap ? speaker_in : mic_in;
  const double fs = sample_rate_hz;
  const double direct_s = distance_m(speaker, mic) / kSpeedOfSoundMps;

  const bool automatic = !(length_s > 0);
  double generate_s = std::min(room.max_length_s, automatic ? estimated_length_s(room, direct_s) : length_s);
  // Bound the work: the images within reach R number (4/3) pi R^3 / V.
  const double volume = room.size_m.x * room.size_m.y * room.size_m.z;
  const double max_reach_m = std::cbrt(kMaxImages * volume * 3 / (4 * std::numbers::pi));
  generate_s = std::min(generate_s, max_reach_m / kSpeedOfSoundMps);
  const auto length = static_cast<std::size_t>(std::ceil(generate_s * fs));
  const double reach_m = static_cast<double>(length) / fs * kSpeedOfSoundMps;

  Images images{{}, {}, {}, length, fs, reach_m, direct_s};
  images.xs =
      axis_images(room.size_m.x, speaker.x, mic.x, room.reflection[kWallX0], room.reflection[kWallX1], reach_m + 1);
  images.ys =
      axis_images(room.size_m.y, speaker.y, mic.y, room.reflection[kWallY0], room.reflection[kWallY1], reach_m + 1);
  images.zs =
      axis_images(room.size_m.z, speaker.z, mic.z, room.reflection[kFloor], room.reflection[kCeiling], reach_m + 1);
  std::vector<float> h = band_filtered_sum(image_trains(room, images, seed), length, fs);
  if (automatic) trim_to_decay(h, direct_s, fs);
  return h;
}

}  // namespace dtmf::sim
