// Signal layer, fast profile: how a candidate window is read, on hand-made windows — each
// band's strongest tone at an offset hypothesis's bins, heard only when it stands over the
// band's floor and rose since the chord before; and the offset a window's own peaks show.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "signal/hop_reader.h"

using namespace dtmf;
using signal::ChordPowers;
using signal::HopWindow;

namespace {
const LinkProfile& p = fast_profile();
constexpr int kLoBin = 100;

HopWindow empty_window() {
  HopWindow w;
  w.power.assign(800, 1.0f);
  w.excess.assign(800, 0.0f);
  return w;
}

int bin_of(int chord, int band, int symbol) {
  return p.hops()
             .band_first_bin[static_cast<std::size_t>(signal::hop_band_set(chord))][static_cast<std::size_t>(band)] +
         symbol;
}

// Chord `chord`'s window: symbol (3 b + chord) % 32 in band b, 20 dB over the floor, its peak
// where a clock `ppm` fast puts it (its amplitude split between the two nearest bins).
HopWindow chord_window(int chord, double ppm) {
  HopWindow w = empty_window();
  for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
    const double at = bin_of(chord, b, (3 * b + chord) % 32) * (1 + ppm * 1e-6);
    const int nearest = static_cast<int>(std::lround(at));
    const double d = at - nearest;
    const auto i = static_cast<std::size_t>(nearest - kLoBin);
    const auto j = d >= 0 ? i + 1 : i - 1;
    w.excess[i] = static_cast<float>(100 * (1 - std::abs(d)) * (1 - std::abs(d)));
    w.excess[j] = static_cast<float>(100 * d * d);
    w.power[i] += w.excess[i];
    w.power[j] += w.excess[j];
    w.band_score[static_cast<std::size_t>(signal::hop_tone_index(signal::hop_band_set(chord), b))] = 100;
  }
  return w;
}

int symbols_right(const signal::HopCandidate& c) {
  int right = 0;
  for (int chord = 0; chord < c.chords; ++chord) {
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const auto& r = c.tones[static_cast<std::size_t>(signal::hop_tone_index(chord, b))];
      right += r.symbol == (3 * b + chord) % 32 && r.heard ? 1 : 0;
    }
  }
  return right;
}
}  // namespace

TEST(HopReader, EachBandsToneIsReadAtTheHypothesissBins) {
  const signal::HopReader reader(p, kLoBin, 32);
  const HopWindow before = empty_window(), first = chord_window(0, 1800), second = chord_window(1, 1800);
  const std::vector<const ChordPowers*> windows{&before, &first, &second};
  const signal::HopCandidate right = reader.read(2, 1800, windows);
  EXPECT_EQ(symbols_right(right), 16);
  EXPECT_EQ(right.offset_ppm, 1800);
  // The runner-up is at most the split tone's other half, in the next symbol's bins.
  for (std::size_t t = 0; t < 16; ++t) EXPECT_GT(right.tones[t].certainty, 1.1f) << t;
  // At no offset, the top bands' tones (over a bin away at 1800 ppm) read as their neighbours.
  EXPECT_LT(symbols_right(reader.read(2, 0, windows)), 12);
}

TEST(HopReader, AToneThatWasThereAChordBeforeIsNotHeard) {
  const signal::HopReader reader(p, kLoBin, 32);
  const HopWindow first = chord_window(0, 0), second = chord_window(1, 0);
  // The window before the frame already held the first chord's tones: a tail, or a held chord.
  const std::vector<const ChordPowers*> windows{&first, &first, &second};
  const signal::HopCandidate c = reader.read(2, 0, windows);
  for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
    const auto& r = c.tones[static_cast<std::size_t>(signal::hop_tone_index(0, b))];
    EXPECT_EQ(r.symbol, (3 * b) % 32);
    EXPECT_FALSE(r.risen);
    EXPECT_FALSE(r.heard);
  }
}

TEST(HopReader, AWindowsOwnPeaksGiveItsOffset) {
  const signal::HopReader reader(p, kLoBin, 32);
  for (const double ppm : {-2500.0, -700.0, 0.0, 900.0, 2200.0}) {
    const HopWindow first = chord_window(0, ppm), second = chord_window(1, ppm);
    const std::vector<const HopWindow*> chords{&first, &second};
    EXPECT_NEAR(reader.blind_offset_ppm(chords), ppm, 100) << ppm;
  }
}
