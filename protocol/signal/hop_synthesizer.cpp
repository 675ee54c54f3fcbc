#include "signal/hop_synthesizer.h"

#include <cmath>
#include <numbers>

namespace dtmf::signal {

namespace {

// Adds a tone on `bin` of a `window`-sample grid to out, faded in and out over `edge` samples.
void add_tone(std::span<float> out, double bin, int window, int edge, double amplitude, double phase) {
  // The sine by rotation (a benchmark renders millions of tones); double keeps it exact
  // to far below a 16-bit sample over a chord.
  const double step = 2.0 * std::numbers::pi * bin / window;
  const double cos_step = std::cos(step), sin_step = std::sin(step);
  double c = std::cos(phase), s = std::sin(phase);
  const auto n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    double gain = amplitude;
    const std::size_t near = std::min(i, n - 1 - i);
    if (near < static_cast<std::size_t>(edge))
      gain *= 0.5 - 0.5 * std::cos(std::numbers::pi * (static_cast<double>(near) + 0.5) / edge);
    out[i] += static_cast<float>(gain * s);
    const double next_s = s * cos_step + c * sin_step;
    c = c * cos_step - s * sin_step;
    s = next_s;
  }
}

double newman_phase(int index, int count) { return std::numbers::pi * index * index / count; }

}  // namespace

std::array<double, kHoppedFrameTones> frame_tones_hz(const LinkProfile& profile, const HoppedSymbols& symbols) {
  const HopLink& h = profile.hops;
  const double step_hz = static_cast<double>(profile.sample_rate_hz) / h.window_samples;
  std::array<double, kHoppedFrameTones> hz{};
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < HopLink::kBandsPerChord; ++b) {
      const auto t = static_cast<std::size_t>(c * HopLink::kBandsPerChord + b);
      hz[t] = (h.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] + symbols[t]) * step_hz;
    }
  }
  return hz;
}

std::vector<float> synthesize_hopped_frame(const LinkProfile& profile, const HoppedSymbols& symbols) {
  const HopLink& h = profile.hops;
  std::vector<float> audio(static_cast<std::size_t>(h.frame_samples()), 0.0f);
  for (int c = 0; c < 2; ++c) {
    auto chord = std::span<float>(audio).subspan(static_cast<std::size_t>(c * h.chord_samples()),
                                                 static_cast<std::size_t>(h.chord_samples()));
    for (int b = 0; b < HopLink::kBandsPerChord; ++b) {
      const auto t = static_cast<std::size_t>(c * HopLink::kBandsPerChord + b);
      const int bin = h.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] + symbols[t];
      add_tone(chord, bin, h.window_samples, h.edge_samples, h.tone_amplitude,
               newman_phase(b, HopLink::kBandsPerChord));
    }
  }
  return audio;
}

std::vector<float> synthesize_hopped_reply(const LinkProfile& profile, const std::array<std::uint8_t, 4>& tone_index) {
  const HopLink& h = profile.hops;
  std::vector<float> audio(static_cast<std::size_t>(h.reply_samples()), 0.0f);
  for (std::size_t b = 0; b < 4; ++b) {
    add_tone(audio, h.reply_band_first_bin[b] + tone_index[b], h.reply_window_samples, h.reply_edge_samples,
             h.reply_amplitude, newman_phase(static_cast<int>(b), 4));
  }
  return audio;
}

}  // namespace dtmf::signal
