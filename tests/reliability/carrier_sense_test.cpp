#include "reliability/carrier_sense.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
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
  // The tail is judged on its envelope, the loudest block of the last kFloorSmoothMs: it has
  // fallen into the noise once every block of the last 20 ms has.
  EXPECT_DOUBLE_EQ(*sense.quiet_since_ms(), t - 200 + kFloorSmoothMs);
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

TEST(OwnAnswerSpan, IsWhereOurRobotsLastAnswerCameOrAllItsSilenceBeforeItFirstAnswers) {
  const AirSpan known = own_answer_span(1000, 40.0, 350, 60);
  EXPECT_DOUBLE_EQ(known.from_ms, 1040 - kOwnLatencyMs);
  EXPECT_DOUBLE_EQ(known.to_ms, 1100 + kOwnLatencyMs);
  const AirSpan unknown = own_answer_span(1000, std::nullopt, 350, 60);
  EXPECT_DOUBLE_EQ(unknown.from_ms, 1000 - kOwnLatencyMs);
  EXPECT_DOUBLE_EQ(unknown.to_ms, 1410 + kOwnLatencyMs);
}

// A lone sender whose robot's first answer sounded but was not read (too weak, or garbled
// by the room) took that answer for another sender's, and yielded for a minute.
TEST(CarrierSense, ARobotsFirstAnswerHeardButNotReadIsOurs) {
  for (const bool with_span : {true, false}) {
    CarrierSense sense;
    double t = hear_for(sense, 0, 1000, kNoiseDbfs);
    sense.own_begin(t);
    t = hear_for(sense, t, 150, -10);
    sense.frame_ended(t);
    const double frame_end_ms = t;
    t = hear_for(sense, t, 200, kNoiseDbfs);
    t = hear_for(sense, t, 60, -30);  // the answer, 200 ms after the frame
    t = hear_for(sense, t, 200, kNoiseDbfs);
    sense.own_end(t, with_span ? std::optional(own_answer_span(frame_end_ms, std::nullopt, 350, 60)) : std::nullopt);
    if (with_span)
      EXPECT_EQ(sense.busy_blocks(), 0u);
    else
      EXPECT_GT(sense.busy_blocks(), 0u) << "without the span, the answer counts as another's";
  }
}

// On a flat air our sound stops at once. Its tail must end as soon, or another's frame that
// starts just after ours is taken for our tail (a tail smoothed over 20 ms from -10 dBFS
// stayed over -30 dBFS for 30 ms more, and three senders then started 466 frames into
// another's exchange in 10 minutes, against 6).
TEST(CarrierSense, AnothersSoundJustAfterOursEndedAtOnceIsHeard) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  t = hear_for(sense, t, kOwnLatencyMs, -10);  // still arriving (the capture latency)
  t = hear_for(sense, t, 30, kNoiseDbfs);
  const double onset_ms = t;
  t = hear_for(sense, t, 60, -30);
  ASSERT_TRUE(sense.last_busy_ms());
  EXPECT_EQ(sense.busy_blocks(), static_cast<std::size_t>(60 / kBlockMs)) << "heard from its first block on";
  EXPECT_DOUBLE_EQ(*sense.last_busy_ms(), t);
  EXPECT_GT(t, onset_ms);
}

TEST(CarrierSense, AnAnswerReadDuringOurExchangeIsOursAndAfterItAnothers) {
  CarrierSense sense;
  sense.own_begin(1000);
  sense.frame_ended(1100);
  sense.answer_read(1180);
  EXPECT_FALSE(sense.answered_exchange_ms()) << "our robot's answer";
  sense.own_end(1190, AirSpan{1120, 1200});
  sense.answer_read(1600);
  ASSERT_TRUE(sense.answered_exchange_ms());
  EXPECT_EQ(*sense.answered_exchange_ms(), 1600);
}

// Under our exchange every sound is ours, another sender's frames too; an answer that names a
// robot none of ours (read by the sender, which knows its robots) is the sign of them.
TEST(CarrierSense, AnAnswerOfAnothersRobotReadUnderOurExchangeIsAnothersSound) {
  CarrierSense sense;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  sense.own_begin(t);
  t = hear_for(sense, t, 100, -10);
  sense.frame_ended(t);
  t = hear_for(sense, t, 50, -10);  // the other's frame goes on, taken for our tail
  EXPECT_FALSE(sense.last_busy_ms());
  sense.answer_masked(t - 20);
  sense.own_end(t);
  ASSERT_TRUE(sense.last_busy_ms());
  EXPECT_EQ(*sense.last_busy_ms(), t - 20);
  EXPECT_EQ(sense.masked_answers(), 1u);
  EXPECT_EQ(sense.others_answers(), 0u);
  EXPECT_FALSE(sense.answered_exchange_ms()) << "the other's next frame may be under way: no short quiet";
}
