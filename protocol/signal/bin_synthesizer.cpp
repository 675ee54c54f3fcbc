#include "signal/bin_synthesizer.h"

#include <algorithm>
#include <span>

#include "signal/synthesizer.h"

namespace dtmf::signal {

namespace {
double bin_hz(const LinkProfile& profile, int bin, int window_samples) {
  return static_cast<double>(bin) * profile.sample_rate_hz / window_samples;
}
double edge_ms(const LinkProfile& profile, int edge_samples) {
  return 1000.0 * edge_samples / profile.sample_rate_hz;
}
}  // namespace

std::array<double, kFrameBands> symbol_tones_hz(const LinkProfile& profile,
                                                const std::array<std::uint8_t, kFrameBands>& symbols) {
  const BinLink& b = profile.bins;
  std::array<double, kFrameBands> tones{};
  for (std::size_t i = 0; i < kFrameBands; ++i) {
    tones[i] = bin_hz(profile, b.band_first_bin[i % 4] + (symbols[i] % b.tones_per_band), b.window_samples);
  }
  return tones;
}

std::vector<float> synthesize_symbols(const LinkProfile& profile, const std::array<std::uint8_t, kFrameBands>& symbols) {
  const BinLink& b = profile.bins;
  const auto chord = static_cast<std::size_t>(b.chord_samples());
  const auto all_tones = symbol_tones_hz(profile, symbols);
  std::vector<float> out(chord * 2, 0.0f);
  for (std::size_t c = 0; c < 2; ++c) {
    std::array<double, 4> tones{};
    std::copy_n(all_tones.begin() + static_cast<std::ptrdiff_t>(c * 4), 4, tones.begin());
    add_chord(std::span<float>(out).subspan(c * chord, chord), tones, b.tone_amplitude,
              edge_ms(profile, b.edge_samples), profile.sample_rate_hz);
  }
  return out;
}

std::vector<float> synthesize_named_reply(const LinkProfile& profile, const NamedReply& reply) {
  const BinLink& b = profile.bins;
  std::vector<float> out(static_cast<std::size_t>(b.reply_samples()), 0.0f);
  const auto idx = reply_tone_indexes(reply);
  const std::array<double, 2> tones{bin_hz(profile, b.reply_band_first_bin[0] + idx[0], b.reply_window_samples),
                                    bin_hz(profile, b.reply_band_first_bin[1] + idx[1], b.reply_window_samples)};
  add_chord(out, tones, b.reply_amplitude, edge_ms(profile, b.reply_edge_samples), profile.sample_rate_hz);
  return out;
}

}  // namespace dtmf::signal
