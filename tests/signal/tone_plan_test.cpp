// Signal layer: the tone plan, frames to chords and back.
#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/tone_plan.h"

using namespace dtmf;
using namespace dtmf::signal;

TEST(TonePlan, SeedBandsSpan2500HzWithSixteenTonesEach) {
  const TonePlan& plan = seed_profile().tones;
  EXPECT_EQ(chord_for(plan, 0x0000), (Chord{4500, 7500, 10500, 13500}));
  const Chord top = chord_for(plan, 0xFFFF);
  EXPECT_NEAR(top[0], 7000, 1e-9);
  EXPECT_NEAR(top[1], 10000, 1e-9);
  EXPECT_NEAR(top[2], 13000, 1e-9);
  EXPECT_NEAR(top[3], 16000, 1e-9);
}

TEST(TonePlan, MostSignificantNibbleGoesToTheLowestBand) {
  const TonePlan& plan = seed_profile().tones;
  // The seed's example frame 1011 0010 1101 1101: nibbles 11, 2, 13, 13.
  const Chord chord = chord_for(plan, 0b1011001011011101);
  const double step = 2500.0 / 15;
  EXPECT_NEAR(chord[0], 4500 + 11 * step, 1e-9);
  EXPECT_NEAR(chord[1], 7500 + 2 * step, 1e-9);
  EXPECT_NEAR(chord[2], 10500 + 13 * step, 1e-9);
  EXPECT_NEAR(chord[3], 13500 + 13 * step, 1e-9);
}

TEST(TonePlan, EveryFrameRoundTripsThroughItsChord) {
  const TonePlan& plan = seed_profile().tones;
  for (std::uint32_t f = 0; f < 65536; ++f) {
    ASSERT_EQ(frame_for(plan, chord_for(plan, static_cast<std::uint16_t>(f))), f);
  }
}

TEST(TonePlan, PeaksMatchPlanTonesOnlyWithinTolerance) {
  const TonePlan& plan = seed_profile().tones;
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

TEST(TonePlan, RepliesUseTheSeedsTwoToneChords) {
  const TonePlan& plan = seed_profile().tones;
  EXPECT_EQ(reply_tones(plan, Reply::Ack), (std::array<double, 2>{2500, 3500}));
  EXPECT_EQ(reply_tones(plan, Reply::Nack), (std::array<double, 2>{2000, 3000}));
}
