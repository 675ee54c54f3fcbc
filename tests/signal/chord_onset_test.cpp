// Where a chord began, from its tones' rise across windows a hop apart (signal/chord_onset.h):
// amplitudes made from the rectangular window's overlap with the chord, as a tone on its bin gives.
#include "signal/chord_onset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace dtmf;

namespace {
constexpr int kWindowSamples = 1920, kHopSamples = 492, kSteadySamples = 2412;

// The summed amplitude of a chord's tones whose steady part runs [steady_start, steady_start +
// kSteadySamples), in windows starting k hops after sample 0, over `floor`.
std::vector<float> amplitudes(double steady_start, int windows, float floor) {
  std::vector<float> a;
  for (int k = 0; k < windows; ++k) {
    const double from = static_cast<double>(k) * kHopSamples, to = from + kWindowSamples;
    const double overlap = std::max(0.0, std::min(to, steady_start + kSteadySamples) - std::max(from, steady_start));
    a.push_back(floor + static_cast<float>(8.0 * overlap / kWindowSamples));
  }
  return a;
}
}  // namespace

TEST(ChordOnset, TheSteadyStartIsFoundToASampleWhereverItLiesBetweenTheWindows) {
  // From just after window 0 ends to where the last window still reaches the plateau.
  for (double start = kWindowSamples + 1; start < 7 * kHopSamples; start += 37) {
    const auto found = signal::chord_steady_start(amplitudes(start, 11, 0.2f), kWindowSamples, kHopSamples, 2.0f);
    ASSERT_TRUE(found) << start;
    EXPECT_NEAR(*found, start, 1.0) << start;
  }
}

TEST(ChordOnset, TheFallingSideAndLaterWindowsDoNotMoveIt) {
  // The same chord seen in 8 windows and in 14 (these reach past its end into silence).
  const double start = 2500;
  const auto few = signal::chord_steady_start(amplitudes(start, 8, 0.2f), kWindowSamples, kHopSamples, 2.0f);
  const auto many = signal::chord_steady_start(amplitudes(start, 14, 0.2f), kWindowSamples, kHopSamples, 2.0f);
  ASSERT_TRUE(few && many);
  EXPECT_NEAR(*few, start, 1.0);
  EXPECT_NEAR(*many, start, 1.0);
}

TEST(ChordOnset, NoRiseOrNoWindowBeforeTheChordPlacesNothing) {
  EXPECT_FALSE(signal::chord_steady_start(std::vector<float>(10, 3.0f), kWindowSamples, kHopSamples, 2.0f));
  // Tones only 1.5 times their floor: too weak to time.
  std::vector<float> weak = amplitudes(2500, 11, 0.0f);
  for (float& a : weak) a = 16.0f + a;
  EXPECT_FALSE(signal::chord_steady_start(weak, kWindowSamples, kHopSamples, 2.0f));
  // Window 0 already inside the chord: its start is not in these windows.
  EXPECT_FALSE(signal::chord_steady_start(amplitudes(-200, 11, 0.2f), kWindowSamples, kHopSamples, 2.0f));
  EXPECT_FALSE(signal::chord_steady_start(std::vector<float>{1.0f}, kWindowSamples, kHopSamples, 2.0f));
}
