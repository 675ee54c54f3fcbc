// Signal layer: the tone plan, frames to chords and back.
#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/tone_plan.h"

using namespace dtmf;
using namespace dtmf::signal;

TEST(TonePlan, SeedBandsSpan2500HzWithSixteenTonesEach) {
  const TonePlan& plan = seed_profile().words().tones;
  EXPECT_EQ(chord_for(plan, 0x0000), (Chord{4500, 7500, 10500, 13500}));
  const Chord top = chord_for(plan, 0xFFFF);
  EXPECT_NEAR(top[0], 7000, 1e-9);
  EXPECT_NEAR(top[1], 10000, 1e-9);
  EXPECT_NEAR(top[2], 13000, 1e-9);
  EXPECT_NEAR(top[3], 16000, 1e-9);
}

TEST(TonePlan, MostSignificantNibbleGoesToTheLowestBand) {
  const TonePlan& plan = seed_profile().words().tones;
  // The seed's example frame 1011 0010 1101 1101: nibbles 11, 2, 13, 13.
  const Chord chord = chord_for(plan, 0b1011001011011101);
  const double step = 2500.0 / 15;
  EXPECT_NEAR(chord[0], 4500 + 11 * step, 1e-9);
  EXPECT_NEAR(chord[1], 7500 + 2 * step, 1e-9);
  EXPECT_NEAR(chord[2], 10500 + 13 * step, 1e-9);
  EXPECT_NEAR(chord[3], 13500 + 13 * step, 1e-9);
}

TEST(TonePlan, EveryFrameRoundTripsThroughItsChord) {
  const TonePlan& plan = seed_profile().words().tones;
  for (std::uint32_t f = 0; f < 65536; ++f) {
    ASSERT_EQ(frame_for(plan, chord_for(plan, static_cast<std::uint16_t>(f))), f);
  }
}

TEST(TonePlan, PeaksMatchPlanTonesOnlyWithinTolerance) {
  const TonePlan& plan = seed_profile().words().tones;
  const auto exact = match_plan_tone(plan, 7500 + 5 * plan.step_hz, 25);
  ASSERT_TRUE(exact);
  EXPECT_EQ(exact->band, 1);
  EXPECT_EQ(exact->nibble, 5);
  EXPECT_TRUE(match_plan_tone(plan, 4500 + 24, 25));
  EXPECT_FALSE(match_plan_tone(plan, 4500 + 26, 25));
  EXPECT_FALSE(match_plan_tone(plan, 7250, 25));   // between bands
  EXPECT_FALSE(match_plan_tone(plan, 3000, 25));   // below the plan
  EXPECT_FALSE(match_plan_tone(plan, 16500, 25));  // above the plan
}

TEST(TonePlan, BandsWithinReachHoldEveryBandThatMatchesInTheRange) {
  const TonePlan& plan = seed_profile().words().tones;
  EXPECT_EQ(bands_within_reach(plan, 8000, 8100, 25), 0b0010u);
  EXPECT_EQ(bands_within_reach(plan, 6990, 7480, 25), 0b0011u);  // 7000 + 25 and 7500 - 25 both in reach
  EXPECT_EQ(bands_within_reach(plan, 7030, 7470, 25), 0u);       // wholly between bands 0 and 1
  EXPECT_EQ(bands_within_reach(plan, 3000, 4470, 25), 0u);
  EXPECT_EQ(bands_within_reach(plan, 4000, 17000, 25), 0b1111u);
  // The superset the offset search relies on: a band that matches any frequency of the range
  // is within reach (ranges as wide as 3000 ppm of offset, and narrower).
  for (double low = 4000; low < 17000; low += 7.3) {
    for (const double width : {0.0, 2.0, 30.0, 100.0}) {
      const unsigned reach = bands_within_reach(plan, low, low + width, 25);
      for (double hz = low; hz <= low + width; hz += 0.5) {
        for (int band = 0; band < 4; ++band) {
          if (match_band_tone(plan, band, hz, 25)) {
            ASSERT_TRUE(reach & (1u << band)) << hz << " Hz matches band " << band << " outside its reach";
          }
        }
        const auto tone = match_plan_tone(plan, hz, 25);
        if (tone) {
          EXPECT_EQ(tone->nibble, match_band_tone(plan, tone->band, hz, 25)->nibble);
        }
      }
    }
  }
}

TEST(TonePlan, RepliesUseTheSeedsTwoToneChords) {
  const TonePlan& plan = seed_profile().words().tones;
  EXPECT_EQ(reply_tones(plan, Reply::Ack), (std::array<double, 2>{2500, 3500}));
  EXPECT_EQ(reply_tones(plan, Reply::Nack), (std::array<double, 2>{2000, 3000}));
}
