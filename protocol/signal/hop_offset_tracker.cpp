#include "signal/hop_offset_tracker.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dtmf::signal {

namespace {
// The most the middle half of a frame's tones may disagree on their offset to be tracked:
// a quarter bin at 10 kHz.
constexpr float kTrackSpreadPpm = 600.0f;
}  // namespace

void HopOffsetTracker::confirm(const HopCandidate& candidate, std::span<const std::uint8_t> symbols) {
  // Each tone sent on bin f was heard at f (1 + offset): the median over the tones the
  // decoder did not have to correct.
  std::array<float, kMaxFrameTones> offsets{};
  std::size_t n = 0;
  for (int chord = 0; chord < candidate.chords; ++chord) {
    const auto set = static_cast<std::size_t>(hop_band_set(chord));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const std::size_t t = static_cast<std::size_t>(hop_tone_index(chord, b));
      if (t >= symbols.size() || candidate.tones[t].symbol != symbols[t] || !candidate.tones[t].heard) continue;
      const float sent_bin = static_cast<float>(plan_.band_first_bin[set][static_cast<std::size_t>(b)] + symbols[t]);
      offsets[n++] = (candidate.peak_bins[t] / sent_bin - 1.0f) * 1e6f;
    }
  }
  if (n < 8) return;
  std::sort(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(n));
  const float median = offsets[n / 2];
  // Only a window wholly inside both chords gives every tone's true position; one that
  // straddles a chord's edge smears each tone over its neighbours, and the two-bin estimate
  // then errs by up to half a bin either way. Such windows decode too (the code corrects),
  // but their offsets scatter: track only an estimate whose middle half agrees.
  const float spread = offsets[3 * n / 4] - offsets[n / 4];
  if (spread > kTrackSpreadPpm) return;
  tracked_ppm_ = static_cast<int>(std::lround(median));
}

}  // namespace dtmf::signal
