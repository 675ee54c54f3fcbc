// Signal layer: the frequency offset the fast listener tracks from decoded frames — the
// median of the tones the decoder did not correct, only when they agree.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "signal/hop_offset_tracker.h"

using namespace dtmf;

namespace {
const LinkProfile& p = fast_profile();

// A two-chord candidate that heard symbol 5 in every band at `ppm` (tone t at ppm_of(t)).
template <class PpmOf>
signal::HopCandidate heard_at(PpmOf ppm_of) {
  signal::HopCandidate c;
  for (int chord = 0; chord < 2; ++chord) {
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const auto t = static_cast<std::size_t>(signal::hop_tone_index(chord, b));
      c.tones[t].symbol = 5;
      const double sent = p.hops().band_first_bin[static_cast<std::size_t>(chord)][static_cast<std::size_t>(b)] + 5;
      c.peak_bins[t] = static_cast<float>(sent * (1 + ppm_of(t) * 1e-6));
    }
  }
  return c;
}
const std::vector<std::uint8_t> kFives(16, 5);
}  // namespace

TEST(HopOffsetTracker, AFramesTonesGiveTheOffsetTheNextFramesAreReadAt) {
  signal::HopOffsetTracker tracker(p.hops());
  EXPECT_FALSE(tracker.offset_ppm());
  tracker.confirm(heard_at([](std::size_t) { return 800.0; }), kFives);
  ASSERT_TRUE(tracker.offset_ppm());
  EXPECT_NEAR(*tracker.offset_ppm(), 800, 2);
  // Corrected tones (sent as another symbol) do not count; two outliers do not move the median.
  signal::HopCandidate c = heard_at([](std::size_t t) { return t == 3 || t == 9 ? 5000.0 : -400.0; });
  std::vector<std::uint8_t> sent = kFives;
  c.tones[0].symbol = 6;
  tracker.confirm(c, sent);
  EXPECT_NEAR(*tracker.offset_ppm(), -400, 2);
}

TEST(HopOffsetTracker, ScatteredOrTooFewTonesLeaveTheOffsetAsItWas) {
  signal::HopOffsetTracker tracker(p.hops());
  tracker.confirm(heard_at([](std::size_t) { return 300.0; }), kFives);
  // A window astride a chord's edge: the middle half disagrees by more than 600 ppm.
  tracker.confirm(heard_at([](std::size_t t) { return t % 2 ? 1500.0 : -1500.0; }), kFives);
  EXPECT_NEAR(*tracker.offset_ppm(), 300, 2);
  // Only 7 tones heard as sent.
  signal::HopCandidate few = heard_at([](std::size_t) { return 1000.0; });
  for (std::size_t t = 7; t < 16; ++t) few.tones[t].heard = false;
  tracker.confirm(few, kFives);
  EXPECT_NEAR(*tracker.offset_ppm(), 300, 2);
}
