// Signal layer, fast profile: the band scores and the frame gate alone, on hand-made windows —
// a band scores its best excess over its other bins' mean power, and a frame shape opens the
// gate only when every chord has `gate_bands` loud bands (a re-read only a band short).
#include <gtest/gtest.h>

#include <vector>

#include "signal/hop_band_gate.h"
#include "signal/hop_candidate.h"
#include "units/decibels.h"

using namespace dtmf;
using signal::HopBandGate;
using signal::HopWindow;

namespace {
const LinkProfile& p = fast_profile();
constexpr int kLoBin = 100;  // any bin under the lowest band, less its margin

HopWindow flat_window() {
  HopWindow w;
  w.power.assign(800, 1.0f);
  w.excess.assign(800, 0.0f);
  return w;
}

// Band b of band set s holds one tone `excess_ratio` over its other bins.
void put_tone(HopWindow& w, int set, int band, float excess_ratio) {
  const auto bin = static_cast<std::size_t>(
      p.hops().band_first_bin[static_cast<std::size_t>(set)][static_cast<std::size_t>(band)] + 7 - kLoBin);
  w.excess[bin] = excess_ratio;
  w.power[bin] = excess_ratio;
}

// A window of band set `set` with `loud` of its eight bands 10 dB over their floor.
HopWindow scored(const HopBandGate& gate, int set, int loud) {
  HopWindow w = flat_window();
  for (int b = 0; b < loud; ++b) put_tone(w, set, b, 10.0f);
  gate.score(w);
  return w;
}
}  // namespace

TEST(HopBandGate, ABandScoresItsToneOverTheMeanOfItsOtherBins) {
  const HopBandGate gate(p.hops(), kLoBin);
  HopWindow w = flat_window();
  put_tone(w, 1, 3, 40.0f);
  gate.score(w);
  EXPECT_FLOAT_EQ(w.band_score[static_cast<std::size_t>(signal::hop_tone_index(1, 3))], 40.0f);
  // A band with nothing in it scores no excess at all.
  EXPECT_FLOAT_EQ(w.band_score[static_cast<std::size_t>(signal::hop_tone_index(0, 3))], 0.0f);
}

TEST(HopBandGate, EveryChordNeedsItsLoudBands) {
  const HopBandGate gate(p.hops(), kLoBin);
  const int need = p.hops().gate_bands;
  const HopWindow full0 = scored(gate, 0, 8), full1 = scored(gate, 1, 8);
  const HopWindow short1 = scored(gate, 1, need - 1), reread1 = scored(gate, 1, p.hops().reread_gate_bands);
  const HopWindow two1 = scored(gate, 1, 2);
  using V = HopBandGate::Verdict;
  const std::vector<const HopWindow*> frame{&full0, &full1};
  EXPECT_EQ(gate.judge(frame), V::Open);
  const std::vector<const HopWindow*> one_short{&full0, &short1};
  EXPECT_EQ(gate.judge(one_short), need - 1 >= p.hops().reread_gate_bands ? V::RereadOnly : V::Closed);
  const std::vector<const HopWindow*> at_reread{&full0, &reread1};
  EXPECT_EQ(gate.judge(at_reread), p.hops().reread_gate_bands >= need ? V::Open : V::RereadOnly);
  // Two loud tones in the second chord: a seed chord or a whistle, not a frame.
  const std::vector<const HopWindow*> whistle{&full0, &two1};
  EXPECT_EQ(gate.judge(whistle), V::Closed);
  // The chords' band sets alternate: the first chord's bands heard in the second's set do not count.
  const std::vector<const HopWindow*> same_set{&full0, &full0};
  EXPECT_EQ(gate.judge(same_set), V::Closed);
  // A three-chord (authenticated) shape: the third chord is the even set again.
  const std::vector<const HopWindow*> three{&full0, &full1, &full0};
  EXPECT_EQ(gate.judge(three), V::Open);
}
