// What the room tests measure with: tones, levels, a precise frequency estimate, the
// statistics of a response's fades, and where the measured rooms are.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "sim/acoustic_channel.h"
#include "sim/real_fft.h"

namespace dtmf::room_test {

inline constexpr int kRate = 48000;

inline std::string rir_path(const std::string& name) { return std::string(DTMF_RIR_DIR) + "/" + name; }

inline std::vector<float> tone(double hz, double seconds, double amplitude = 0.5, int rate = kRate) {
  std::vector<float> x(static_cast<std::size_t>(seconds * rate));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(amplitude *
                              std::sin(2 * std::numbers::pi * std::fmod(hz * static_cast<double>(i) / rate, 1.0)));
  }
  return x;
}

inline double rms(std::span<const float> x) {
  double p = 0;
  for (float s : x) p += static_cast<double>(s) * s;
  return std::sqrt(p / static_cast<double>(x.size()));
}

inline double db(double ratio) { return 20 * std::log10(ratio); }

// The band-limited signal between samples (Whittaker-Shannon over +-64 samples).
inline double between_samples(std::span<const float> h, double t) {
  double y = 0;
  const auto centre = static_cast<long long>(std::floor(t));
  for (long long k = centre - 64; k <= centre + 64; ++k) {
    if (k < 0 || k >= static_cast<long long>(h.size())) continue;
    const double x = t - static_cast<double>(k);
    y += h[static_cast<std::size_t>(k)] * (x == 0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x));
  }
  return y;
}

// The time (samples) and height of the largest peak of the band-limited signal within
// `within` samples of `t`.
inline std::pair<double, double> peak_near(std::span<const float> h, double t, double within = 3) {
  double best_t = t, best = 0;
  for (double u = t - within; u <= t + within; u += 0.01) {
    const double v = between_samples(h, u);
    if (std::abs(v) > std::abs(best)) {
      best = v;
      best_t = u;
    }
  }
  return {best_t, best};
}

// All of `in` through the channel as one transmitter, in blocks of `block` samples.
inline std::vector<float> through(sim::AcousticChannel& channel, std::span<const float> in, std::size_t block = 4800) {
  std::vector<float> out;
  for (std::size_t i = 0; i < in.size(); i += block)
    channel.process(in.subspan(i, std::min(block, in.size() - i)), out);
  return out;
}

// The strongest frequency within [low_hz, high_hz]: a Hann-windowed FFT zero-padded to
// 2^21 points (0.023 Hz bins at 48 kHz), refined by a parabola through the log magnitudes.
inline double peak_frequency_hz(std::span<const float> x, double low_hz, double high_hz, int rate = kRate) {
  const sim::RealFft fft(1u << 21);
  sim::FftReal buffer(fft.size(), 0.0f);
  const std::size_t n = std::min(x.size(), fft.size());
  for (std::size_t i = 0; i < n; ++i) {
    buffer[i] = x[i] * static_cast<float>(0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) /
                                                               static_cast<double>(n - 1)));
  }
  sim::FftBins bins(fft.bins());
  fft.forward(buffer.data(), bins.data());
  const double bin_hz = static_cast<double>(rate) / static_cast<double>(fft.size());
  const auto lo = static_cast<std::size_t>(low_hz / bin_hz), hi = static_cast<std::size_t>(high_hz / bin_hz);
  std::size_t best = lo;
  for (std::size_t k = lo; k <= hi; ++k)
    if (std::abs(bins[k]) > std::abs(bins[best])) best = k;
  const double a = std::log(std::abs(bins[best - 1])), b = std::log(std::abs(bins[best])),
               c = std::log(std::abs(bins[best + 1]));
  return (static_cast<double>(best) + 0.5 * (a - c) / (a - 2 * b + c)) * bin_hz;
}

struct FadeStats {
  std::size_t below_10_db = 0;  // frequencies more than 10 dB below the local mean power
  std::size_t below_20_db = 0;
  std::size_t frequencies = 0;

  double fraction_10() const { return static_cast<double>(below_10_db) / static_cast<double>(frequencies); }
  double fraction_20() const { return static_cast<double>(below_20_db) / static_cast<double>(frequencies); }
  FadeStats& operator+=(const FadeStats& o) {
    below_10_db += o.below_10_db;
    below_20_db += o.below_20_db;
    frequencies += o.frequencies;
    return *this;
  }
};

// |H(f)|^2 of a response at 25 Hz steps from 4 to 16 kHz, each against the mean over the
// 1 kHz around it (so that a slow tilt — air absorption, a clap's spectrum — is not taken
// for fading). A diffuse field (Rayleigh fading) has 1 - e^-0.1 = 9.5 % of them 10 dB down,
// 1 - e^-0.01 = 1 % 20 dB down.
inline FadeStats fade_stats(std::span<const float> h, int rate = kRate) {
  constexpr double kStepHz = 25, kLowHz = 4000, kHighHz = 16000;
  constexpr int kLocal = 20;  // +-500 Hz
  const auto per_step = static_cast<std::size_t>(rate / kStepHz);
  const std::size_t m = (h.size() + per_step - 1) / per_step;  // FFT of m * per_step points: bins every 25 / m Hz
  const sim::RealFft fft(m * per_step);
  sim::FftReal x(fft.size(), 0.0f);
  std::copy(h.begin(), h.end(), x.begin());
  sim::FftBins bins(fft.bins());
  fft.forward(x.data(), bins.data());
  auto power = [&](double f) {
    return static_cast<double>(std::norm(bins[static_cast<std::size_t>(std::lround(f / kStepHz)) * m]));
  };
  FadeStats s;
  for (double f = kLowHz; f <= kHighHz; f += kStepHz) {
    double mean = 0;
    for (int k = -kLocal; k <= kLocal; ++k) mean += power(f + k * kStepHz) / (2 * kLocal + 1);
    ++s.frequencies;
    if (power(f) < 0.1 * mean) ++s.below_10_db;
    if (power(f) < 0.01 * mean) ++s.below_20_db;
  }
  return s;
}

// The impulse response of a channel with one transmitter: a click through it.
inline std::vector<float> impulse_response(sim::AcousticChannel& channel, double seconds, int rate = kRate) {
  std::vector<float> click(static_cast<std::size_t>(seconds * rate), 0.0f);
  click[0] = 1.0f;
  return through(channel, click);
}

}  // namespace dtmf::room_test
