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

std::vector<double> frame_tones_hz(const LinkProfile& profile, std::span<const std::uint8_t> symbols) {
  const HopPlan& h = profile.hops();
  const double step_hz = static_cast<double>(profile.sample_rate_hz) / h.window_samples;
  std::vector<double> hz(symbols.size());
  for (std::size_t t = 0; t < symbols.size(); ++t) {
    const std::size_t c = t / HopPlan::kBandsPerChord, b = t % HopPlan::kBandsPerChord;
    hz[t] = (h.band_first_bin[c % 2][b] + symbols[t]) * step_hz;
  }
  return hz;
}

std::vector<float> synthesize_hopped_frame(const LinkProfile& profile, std::span<const std::uint8_t> symbols) {
  const HopPlan& h = profile.hops();
  const std::size_t chords = symbols.size() / HopPlan::kBandsPerChord;
  std::vector<float> audio(chords * static_cast<std::size_t>(h.chord_samples()), 0.0f);
  for (std::size_t c = 0; c < chords; ++c) {
    auto chord = std::span<float>(audio).subspan(c * static_cast<std::size_t>(h.chord_samples()),
                                                 static_cast<std::size_t>(h.chord_samples()));
    for (std::size_t b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const std::size_t t = c * HopPlan::kBandsPerChord + b;
      add_tone(chord, h.band_first_bin[c % 2][b] + symbols[t], h.window_samples, h.edge_samples, h.tone_amplitude,
               newman_phase(static_cast<int>(b), HopPlan::kBandsPerChord));
    }
  }
  return audio;
}

std::vector<float> synthesize_hopped_reply(const LinkProfile& profile, const reliability::ReplyTones& tones, int lane) {
  const HopPlan& h = profile.hops();
  std::vector<float> audio(static_cast<std::size_t>(h.reply_samples()), 0.0f);
  for (int c = 0; c < HopPlan::kReplyChords; ++c) {
    auto chord = std::span<float>(audio).subspan(static_cast<std::size_t>(c * h.reply_chord_samples()),
                                                 static_cast<std::size_t>(h.reply_chord_samples()));
    for (int b = 0; b < HopPlan::kReplyBands; ++b) {
      const std::uint8_t tone = tones[static_cast<std::size_t>(c * HopPlan::kReplyBands + b)];
      add_tone(chord, h.reply_bin(lane, b, tone), h.reply_window_samples, h.reply_edge_samples, h.reply_amplitude,
               newman_phase(b, HopPlan::kReplyBands));
    }
  }
  return audio;
}

std::vector<float> synthesize_tag_chord(const LinkProfile& profile, const reliability::TagChordSymbols& symbols) {
  const HopPlan& h = profile.hops();
  std::vector<float> audio(static_cast<std::size_t>(h.tag_samples()), 0.0f);
  for (int k = 0; k < reliability::kTagChordTones; ++k) {
    const auto set = static_cast<std::size_t>(k / HopPlan::kBandsPerChord);
    const auto band = static_cast<std::size_t>(k % HopPlan::kBandsPerChord);
    add_tone(audio, h.band_first_bin[set][band] + symbols[static_cast<std::size_t>(k)], h.window_samples,
             h.edge_samples, h.tag_amplitude, newman_phase(k, reliability::kTagChordTones));
  }
  return audio;
}

}  // namespace dtmf::signal
