// Signal layer: the debouncer's 2-in-0.3 s rule and 0.8 s lockout (seed section 8), and our
// re-arming rule for reverberant rooms.
#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/debouncer.h"

using namespace dtmf;
using namespace dtmf::signal;

namespace {

const DebounceParams& seed() { return seed_profile().debounce; }

bool hit(Debouncer& d, std::uint32_t symbol, double t_ms, double level = 1.0) {
  return d.on_window(t_ms, Debouncer::Detection{symbol, level}).has_value();
}

void miss(Debouncer& d, double t_ms) { EXPECT_FALSE(d.on_window(t_ms, std::nullopt)); }

// A chord of `symbol` that passes at `pass_ms` (second detection) and keeps sounding at
// `level` until `until_ms`, one window every 50 ms.
void sound(Debouncer& d, std::uint32_t symbol, double pass_ms, double until_ms, double level = 1.0) {
  EXPECT_FALSE(hit(d, symbol, pass_ms - 50, level));
  EXPECT_TRUE(hit(d, symbol, pass_ms, level));
  for (double t = pass_ms + 50; t <= until_ms; t += 50) EXPECT_FALSE(hit(d, symbol, t, level)) << t;
}

}  // namespace

TEST(Debouncer, OneDetectionIsNotEnough) {
  Debouncer d(seed());
  EXPECT_FALSE(hit(d, 7, 0));
}

TEST(Debouncer, TwoDetectionsWithin300MsPass) {
  Debouncer d(seed());
  EXPECT_FALSE(d.on_window(1000, Debouncer::Detection{7, 1.0}));
  miss(d, 1100);
  const auto pass = d.on_window(1300, Debouncer::Detection{7, 1.0});
  ASSERT_TRUE(pass);
  EXPECT_EQ(pass->symbol, 7u);
  EXPECT_DOUBLE_EQ(pass->first_detection_ms, 1000);
  EXPECT_DOUBLE_EQ(pass->pass_ms, 1300);
}

TEST(Debouncer, DetectionsFurtherApartThan300MsDoNot) {
  Debouncer d(seed());
  EXPECT_FALSE(hit(d, 7, 0));
  EXPECT_FALSE(hit(d, 7, 301));
  EXPECT_FALSE(hit(d, 7, 602));
}

TEST(Debouncer, OtherSymbolsInBetweenDoNotCount) {
  Debouncer d(seed());
  EXPECT_FALSE(hit(d, 7, 0));
  EXPECT_FALSE(hit(d, 8, 50));
  EXPECT_FALSE(hit(d, 9, 100));
  EXPECT_TRUE(hit(d, 7, 150));
}

TEST(Debouncer, AChordThatKeepsSoundingPassesOnce) {
  Debouncer d(seed());
  sound(d, 7, 50, 3000);
}

// The seed says 0.8 s; we lock out 0.9 s from the pass (docs/protocol.md §6).
TEST(Debouncer, TheSameChordAfterAGapIsLockedOutFor900Ms) {
  ASSERT_EQ(seed().lockout_ms, 900);
  Debouncer d(seed());
  sound(d, 7, 50, 300);  // passes at 50 ms: locked out until 950 ms
  miss(d, 350);
  // Back within the lockout: ignored, and these detections do not count later either.
  EXPECT_FALSE(hit(d, 7, 400));
  EXPECT_FALSE(hit(d, 7, 450));
  miss(d, 900);
  EXPECT_FALSE(hit(d, 7, 960));
  EXPECT_TRUE(hit(d, 7, 1010));
}

TEST(Debouncer, ADifferentSymbolPassesAtOnceDuringTheLockout) {
  Debouncer d(seed());
  sound(d, 7, 50, 50);
  EXPECT_FALSE(hit(d, 8, 100));
  EXPECT_TRUE(hit(d, 8, 150));
  // After another symbol passed, the first one may pass again at once.
  EXPECT_FALSE(hit(d, 7, 200));
  EXPECT_TRUE(hit(d, 7, 250));
}

TEST(Debouncer, AReverberantTailPastTheLockoutDoesNotPassAgain) {
  Debouncer d(seed());
  sound(d, 7, 100, 800);
  double level = 0.5;
  for (double t = 850; t <= 1300; t += 50, level *= 0.4) EXPECT_FALSE(hit(d, 7, t, level)) << t;
}

// Seen in a simulated room (pink noise, RT60 0.3 s): the chord's last window, half chord
// and half silence, detected nothing; the tail 26 and 40 dB down then passed after the
// lockout. A window without the chord must not make its quiet tail a new chord.
TEST(Debouncer, ARaggedLastWindowDoesNotLetTheTailPassAgain) {
  Debouncer d(seed());
  sound(d, 7, 100, 800, 0.18);
  miss(d, 850);
  EXPECT_FALSE(hit(d, 7, 900, 0.009));
  EXPECT_FALSE(hit(d, 7, 950, 0.002));
  miss(d, 1000);
  // The same chord sent again at its own level passes again.
  EXPECT_FALSE(hit(d, 7, 1250, 0.17));
  EXPECT_TRUE(hit(d, 7, 1300, 0.18));
}

TEST(Debouncer, TheSameChordAgainThroughAReverberantGapPassesAgain) {
  Debouncer d(seed());
  sound(d, 7, 100, 900);              // an 0.8 s chord, passed at 100 ms
  EXPECT_FALSE(hit(d, 7, 950, 0.2));  // the 0.2 s gap, filled by the tail
  EXPECT_FALSE(hit(d, 7, 1000, 0.05));
  EXPECT_FALSE(hit(d, 7, 1050, 0.05));
  EXPECT_FALSE(hit(d, 7, 1100, 0.8));  // the same chord again, 1 s after the first: its onset re-arms and counts
  EXPECT_TRUE(hit(d, 7, 1150, 1.0));
}

TEST(Debouncer, AChordsOwnRisingOnsetDoesNotReArmIt) {
  Debouncer d(seed());
  EXPECT_FALSE(hit(d, 7, 0, 0.05));
  EXPECT_TRUE(hit(d, 7, 50, 0.1));  // passed on the first, partial windows
  for (double t = 100; t <= 1500; t += 50) EXPECT_FALSE(hit(d, 7, t, 1.0)) << t;
}

TEST(Debouncer, ThreeDetectionsNeededWhenTheProfileSaysSo) {
  DebounceParams strict = seed();
  strict.min_detections = 3;
  Debouncer d(strict);
  EXPECT_FALSE(hit(d, 1, 0));
  EXPECT_FALSE(hit(d, 1, 50));
  EXPECT_TRUE(hit(d, 1, 100));
}
