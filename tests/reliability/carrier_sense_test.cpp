#include "reliability/carrier_sense.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reliability/heard_blocks.h"

using namespace dtmf::reliability;

namespace {

using dtmf::test_support::hear_for;
using dtmf::test_support::kBlockMs;
constexpr double kNoiseDbfs = -50;

}  // namespace

TEST(BlockLevel, AFullScaleSineIsZeroDbfsAndSilenceTheFloorValue) {
  std::vector<float> sine(4800);
  for (std::size_t i = 0; i < sine.size(); ++i) sine[i] = static_cast<float>(std::sin(2 * M_PI * 1000 * i / 48000.0));
  EXPECT_NEAR(block_level_dbfs(sine), 0, 0.01);
  for (auto& s : sine) s *= 0.01f;
  EXPECT_NEAR(block_level_dbfs(sine), -40, 0.01);
  EXPECT_EQ(block_level_dbfs(std::vector<float>(480, 0.0f)), kSilenceDbfs);
  EXPECT_EQ(block_level_dbfs({}), kSilenceDbfs);
}

TEST(CarrierSense, SteadyNoiseIsTheFloorAndAnothersFrameOverItIsBusy) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 3000, kNoiseDbfs);
  EXPECT_NEAR(sense.floor_dbfs(), kNoiseDbfs, 0.01);
  EXPECT_FALSE(sense.last_busy_ms());
  hear_for(sense, t, 150, kNoiseDbfs + kBusyOverFloorDb - 1);  // under the threshold
  EXPECT_FALSE(sense.last_busy_ms());
  t = hear_for(sense, t + 150, 150, -20);
  EXPECT_TRUE(sense.busy_now());
  EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), t);
  EXPECT_EQ(sense.busy_blocks(), 15u);
}

TEST(CarrierSense, BlocksOfDigitalSilenceAmongTheNoiseDoNotLowerTheFloor) {
  CarrierSense sense;
  double t = 0;
  for (int k = 0; k < 100; ++k) {
    t = hear_for(sense, t, 90, kNoiseDbfs);
    t = hear_for(sense, t, 10, kSilenceDbfs);  // an underrun: 1 block in 10
  }
  EXPECT_NEAR(sense.floor_dbfs(), kNoiseDbfs, 3);
  EXPECT_LT(sense.floor_dbfs(), kNoiseDbfs);
  EXPECT_FALSE(sense.last_busy_ms()) << "the noise was taken for a sound";
}

TEST(CarrierSense, RunsOfFramesDoNotBecomeTheFloorWhileTheAirFallsQuietBetween) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  // 2 s of frames, 150 ms on and 50 ms off, then the quiet of a handover (air_access.h).
  for (int run = 0; run < 6; ++run) {
    for (int k = 0; k < 10; ++k) {
      t = hear_for(sense, t, 150, -20);
      t = hear_for(sense, t, 50, kNoiseDbfs);
    }
    t = hear_for(sense, t, 500, kNoiseDbfs);
  }
  EXPECT_NEAR(sense.floor_dbfs(), kNoiseDbfs, 0.5);
  t = hear_for(sense, t, 150, -20);
  EXPECT_TRUE(sense.busy_now());
}

TEST(CarrierSense, OurOwnExchangeAndItsFallingTailAreNotBusy) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 250, -10);
  sense.own_end(t);
  // A tail falling 30 dB a second (RT60 2 s), to the floor.
  for (double level = -10; level > kNoiseDbfs; level -= 0.3) {
    sense.hear(level, t + kBlockMs);
    t += kBlockMs;
  }
  hear_for(sense, t, 500, kNoiseDbfs);
  EXPECT_FALSE(sense.last_busy_ms()) << "our own sound was taken for another's";
  EXPECT_NEAR(sense.floor_dbfs(), kNoiseDbfs, 0.01) << "our own sound raised the floor";
}

TEST(CarrierSense, AFrameRisingOutOfOurTailIsBusy) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 250, -10);
  sense.own_end(t);
  t = hear_for(sense, t, 300, -30);  // our tail, still 20 dB over the floor
  EXPECT_FALSE(sense.last_busy_ms());
  t = hear_for(sense, t, 50, -15);  // another starts: a rise over the tail
  ASSERT_TRUE(sense.last_busy_ms());
  EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), t);
  // Once it ends, our tail goes on under it: ours, not another's.
  hear_for(sense, t, 50, -31);
  EXPECT_FALSE(sense.busy_now());
  EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), t);
}

TEST(CarrierSense, WhileWeWaitForOurAnswerWhatSoundsIsOursOnlyWithinTheAnswer) {
  for (const bool answered : {true, false}) {
    CarrierSense sense;
    double t = hear_for(sense, 0, 1000, kNoiseDbfs);
    sense.own_begin(t);
    t = hear_for(sense, t, 150, -10);
    sense.frame_ended(t);
    t = hear_for(sense, t, 200, -45);  // our frame's tail, quickly gone
    const double answer_from = t;
    t = hear_for(sense, t, 60, -20);  // our robot's answer, or someone's
    const double answer_to = t;
    t = hear_for(sense, t, 100, -45);
    EXPECT_FALSE(sense.last_busy_ms()) << "a block heard while we wait counted before the wait ended";
    EXPECT_TRUE(sense.own_on());
    sense.own_end(t, answered ? std::optional<AirSpan>({answer_from, answer_to}) : std::nullopt);
    EXPECT_FALSE(sense.own_on());
    if (answered) {
      EXPECT_FALSE(sense.last_busy_ms()) << "our robot's answer was taken for another's";
    } else {
      ASSERT_TRUE(sense.last_busy_ms());
      EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), answer_to);
    }
  }
}

TEST(CarrierSense, TheAirIsQuietOnlyOnceOurTailHasFallenIntoTheNoise) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  ASSERT_TRUE(sense.quiet_since_ms());
  EXPECT_DOUBLE_EQ(*sense.quiet_since_ms(), kBlockMs);
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  EXPECT_FALSE(sense.quiet_since_ms());
  sense.own_end(t);
  t = hear_for(sense, t, 300, -30);
  EXPECT_FALSE(sense.quiet_since_ms()) << "our tail was taken for quiet";
  t = hear_for(sense, t, 200, kNoiseDbfs);
  ASSERT_TRUE(sense.quiet_since_ms());
  // The tail is judged smoothed over kFloorSmoothMs: from 20 dB over the noise it takes
  // 20 ms * ln(99 / (10^0.4 - 1)) = 83.6 ms to fall kTailEndMarginDb under the busy mark.
  const double fall_ms = kFloorSmoothMs * std::log(99 / (std::pow(10, (kBusyOverFloorDb - kTailEndMarginDb) / 10) - 1));
  EXPECT_DOUBLE_EQ(*sense.quiet_since_ms(), t - 200 + std::ceil(fall_ms / kBlockMs) * kBlockMs);
}

// A tone's decay in a room beats: a block far under the tail's envelope, then the tail
// again, is still our tail (carrier_sense_rooms_test.cpp has it through measured rooms).
TEST(CarrierSense, ABlockThatDipsUnderOurTailIsNoRiseAfterIt) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  t = hear_for(sense, t, 150, -25);
  t = hear_for(sense, t, kBlockMs, -45);  // 20 dB under the tail, still over the noise
  hear_for(sense, t, 50, -25);
  EXPECT_FALSE(sense.last_busy_ms());
  EXPECT_EQ(sense.busy_blocks(), 0u);
}

TEST(CarrierSense, ASoundHeldLongerThanAnyTailIsNotOurs) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 250, -20);
  sense.own_end(t);
  // Another's frame began under ours, at our level: no rise to tell it by.
  t = hear_for(sense, t, kOwnTailMaxMs - kBlockMs, -20);
  EXPECT_FALSE(sense.last_busy_ms());
  hear_for(sense, t, 2 * kBlockMs, -20);
  EXPECT_TRUE(sense.busy_now());
}

TEST(CarrierSense, ABlockOverTheMarkAloneIsNoSoundButASoundThatLastsIs) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  const double spike_dbfs = kNoiseDbfs + kBusyOverFloorDb + 3;
  for (int k = 0; k < 5; ++k) {
    t = hear_for(sense, t, kBlockMs, spike_dbfs);  // one block of noise over the mark
    t = hear_for(sense, t, 300, kNoiseDbfs);
  }
  // ... also the first block after our own exchange, where the smoothing resumes.
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  t = hear_for(sense, t, 200, kNoiseDbfs);  // the tail fell at once
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  for (double level = -10; level > kNoiseDbfs; level -= 3) t = hear_for(sense, t, kBlockMs, level);
  t = hear_for(sense, t, kBlockMs, spike_dbfs);
  t = hear_for(sense, t, 300, kNoiseDbfs);
  EXPECT_FALSE(sense.last_busy_ms()) << "a block of noise was taken for a sound";
  // Another's chord, as faint: heard within 50 ms (a slot of air_access.h), and to its end.
  const double from = t;
  t = hear_for(sense, t, 60, spike_dbfs);
  ASSERT_TRUE(sense.last_busy_ms());
  EXPECT_LE(*sense.last_busy_ms() - from, 60);
  EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), t);
  EXPECT_GE(sense.busy_blocks(), 3u);
}
