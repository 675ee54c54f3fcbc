#include "signal/synthesizer.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace dtmf::signal {

void add_chord(std::span<float> out, std::span<const double> tones_hz, double amplitude, double edge_ms,
               int sample_rate_hz) {
  const std::size_t n = out.size();
  const std::size_t edge =
      std::min<std::size_t>(n / 2, static_cast<std::size_t>(std::lround(edge_ms * sample_rate_hz / 1000.0)));
  // Only the chord is faded, not what `out` already holds.
  auto envelope = [&](std::size_t i) {
    const std::size_t from_edge = std::min(i, n - 1 - i);
    if (from_edge >= edge) return 1.0;
    return 0.5 - 0.5 * std::cos(std::numbers::pi * (from_edge + 0.5) / edge);
  };
  for (double f : tones_hz) {
    // A rotating phasor, renormalised now and then, is far cheaper than sin() per sample.
    const double w = 2.0 * std::numbers::pi * f / sample_rate_hz;
    const std::complex<double> step(std::cos(w), std::sin(w));
    std::complex<double> phasor(1.0, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const bool in_edge = i < edge || i + edge >= n;
      const double gain = in_edge ? amplitude * envelope(i) : amplitude;
      out[i] += static_cast<float>(gain * phasor.imag());
      phasor *= step;
      if ((i & 1023) == 1023) phasor /= std::abs(phasor);
    }
  }
}

std::vector<float> synthesize_chord(const LinkProfile& profile, std::span<const double> tones_hz, double duration_ms) {
  std::vector<float> samples(static_cast<std::size_t>(profile.samples_for_ms(duration_ms)), 0.0f);
  add_chord(samples, tones_hz, profile.words().tones.tone_amplitude, profile.words().tones.edge_ms,
            profile.sample_rate_hz);
  return samples;
}

std::vector<float> synthesize_frame(const LinkProfile& profile, std::uint16_t frame) {
  const Chord chord = chord_for(profile.words().tones, frame);
  return synthesize_chord(profile, chord, profile.timing.chord_ms);
}

std::vector<float> synthesize_reply(const LinkProfile& profile, Reply reply) {
  return synthesize_chord(profile, reply_tones(profile.words().tones, reply), profile.timing.ack_ms);
}

}  // namespace dtmf::signal
