#include "reliability/air_access.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "reliability/heard_blocks.h"

using namespace dtmf::reliability;

namespace {

using dtmf::test_support::hear_for;
using dtmf::test_support::kBlockMs;
constexpr double kQuietMs = 400;
constexpr double kNoiseDbfs = -60;

// Our exchange: `ms` of our own sound from `at_ms`; returns its end.
double exchange(CarrierSense& sense, AirAccess& air, double at_ms, double ms) {
  air.started(sense, at_ms);
  sense.own_begin(at_ms);
  const double end = hear_for(sense, at_ms, ms, -10);
  sense.own_end(end);
  return end;
}

}  // namespace

// Hears the noise until `air` lets a frame of `use` start; returns when.
double wait_for_air(CarrierSense& sense, AirAccess& air, double t, AirUse use) {
  for (double at = air.start_at(sense, t, use); at > t; at = air.start_at(sense, t, use))
    t = hear_for(sense, t, std::max(kBlockMs, at - t), kNoiseDbfs);
  return t;
}

TEST(AirAccess, AloneASenderNeverDefersAndPausesToListenOnlyAfterLongRuns) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 1);
  double t = hear_for(sense, 0, 500, kNoiseDbfs);
  double paused_ms = 0;
  const double run_from = t;
  for (int k = 0; k < 180; ++k) {  // 45 s of frames back to back
    const double at = wait_for_air(sense, air, t, AirUse::Command);
    paused_ms += at - t;
    t = exchange(sense, air, at, 250);
  }
  EXPECT_EQ(air.deferred(), 0u);
  EXPECT_EQ(air.yields(), 0u);
  EXPECT_EQ(air.listens(), 2u) << "a pause per " << kListenEveryMs << " ms of frames";
  // Each pause: our sound's capture latency, then the listening window.
  EXPECT_LE(paused_ms, 2 * (kOwnLatencyMs + kListenWindowMs + 2 * kBlockMs));
  EXPECT_GE(paused_ms, 2 * kListenWindowMs);
  EXPECT_LT(paused_ms / (t - run_from), 0.02) << "the cost of listening, alone";

  // Frames with gaps as long as a listening window never pause.
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(air.start_at(sense, t, AirUse::Command), t) << "frame " << k;
    t = exchange(sense, air, t, 250);
    t = hear_for(sense, t, kOwnLatencyMs + kListenWindowMs, kNoiseDbfs);
  }
  EXPECT_EQ(air.listens(), 2u);
}

TEST(AirAccess, ATeleopRenewalNeverPausesToListen) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 1);
  double t = hear_for(sense, 0, 500, kNoiseDbfs);
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(air.start_at(sense, t, AirUse::Renewal), t) << "renewal " << k;
    t = exchange(sense, air, t, 250);
  }
  EXPECT_EQ(air.listens(), 0u);
}

TEST(AirAccess, AfterAnothersSoundItWaitsTheQuietAndABackoffWithinItsWindow) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 7);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);  // another's frame
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t + kQuietMs);
  EXPECT_EQ(air.deferred(), 1u);
  t = hear_for(sense, t, 100, kNoiseDbfs);
  const double quiet_from = *sense.quiet_since_ms();
  const double at = air.start_at(sense, t, AirUse::Command);
  EXPECT_GE(at, quiet_from + kQuietMs);
  EXPECT_LE(at, quiet_from + kQuietMs + (kBackoffSlots - 1) * kSlotMs);
  // The draw holds for this deferral; another sound heard meanwhile moves it.
  t = hear_for(sense, t, 100, kNoiseDbfs);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Command), at);
  t = hear_for(sense, t, 100, -20);
  t = hear_for(sense, t, 10, kNoiseDbfs);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Command), at + (*sense.quiet_since_ms() - quiet_from));
  EXPECT_EQ(air.deferred(), 1u);
}

// Another's frame, its robot's silence, and the answer our ear read: that exchange is over,
// and a short quiet will do, after the answer's tail too (a room's, beating as it falls). A
// sound that rises over that tail is a new frame, whose answer is awaited.
TEST(AirAccess, AfterAnAnswerItReadEndedAnothersExchangeItHoldsOnlyAShortQuiet) {
  enum class After { Nothing, ItsTail, AFrame };
  for (const After after : {After::Nothing, After::ItsTail, After::AFrame}) {
    SCOPED_TRACE(after == After::Nothing ? "the answer last" : after == After::ItsTail ? "its tail" : "a frame");
    CarrierSense sense;
    constexpr double kSeedQuietMs = 700;  // longer than the short quiet and the longest backoff
    AirAccess air(kSeedQuietMs, 7);
    double t = hear_for(sense, 0, 1000, kNoiseDbfs);
    t = hear_for(sense, t, 200, -20);  // another's frame
    t = hear_for(sense, t, 60, kNoiseDbfs);
    t = hear_for(sense, t, 40, -25);  // its robot's answer
    sense.answer_read(t);
    if (after == After::ItsTail) {
      // 300 ms falling 30 dB, every third block dipping 12 dB under the envelope and back.
      for (int k = 0; k < 60; ++k) t = hear_for(sense, t, kBlockMs, -25 - 0.5 * k - (k % 3 == 1 ? 12 : 0));
    }
    if (after == After::AFrame) t = hear_for(sense, t, 200, -12);
    t = hear_for(sense, t, 2 * kBlockMs, kNoiseDbfs);
    const double quiet_from = *sense.quiet_since_ms();
    const double at = air.start_at(sense, t, AirUse::Command);
    t = wait_for_air(sense, air, t, AirUse::Command);
    air.started(sense, t);
    EXPECT_EQ(air.answered_waits(), after == After::AFrame ? 0u : 1u);
    if (after == After::AFrame) {
      EXPECT_GE(at, quiet_from + kSeedQuietMs);
    } else {
      EXPECT_GE(at, quiet_from + kStarvedQuietMs);
      EXPECT_LE(at, quiet_from + kStarvedQuietMs + (kBackoffSlots - 1) * kSlotMs);
    }
  }
}

TEST(AirAccess, ADeferringSenderWaitsForItsOwnTailToFallBeforeItCountsTheQuiet) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 7);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);  // another's frame: we defer
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t);
  // A stop of ours went out meanwhile; its tail stays 20 dB over the floor for a second.
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  t = hear_for(sense, t, 1000, -30);
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t + kQuietMs - kBlockMs) << "our tail was taken for quiet";
}

TEST(AirAccess, BackoffsAreDrawnAtRandomSoTwoWaitingSendersSeldomStartTogether) {
  std::set<double> backoffs;
  for (std::uint64_t seed = 0; seed < 64; ++seed) {
    CarrierSense sense;
    AirAccess air(kQuietMs, seed);
    double t = hear_for(sense, 0, 1000, kNoiseDbfs);
    t = hear_for(sense, t, 100, -20);
    backoffs.insert(air.start_at(sense, t, AirUse::Command) - (*sense.last_busy_ms() + kQuietMs));
  }
  EXPECT_EQ(backoffs.size(), static_cast<std::size_t>(kBackoffSlots)) << "every slot drawn in 64 tries";
}

TEST(AirAccess, AStopWaitsOnlyWhileAnotherSoundsNow) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 3);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Stop), *sense.last_busy_ms() + kBusyNowMs);
  t = hear_for(sense, t, kBusyNowMs, kNoiseDbfs);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Stop), t) << "a stop waited for the quiet hold";
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t);
}

TEST(AirAccess, AStopWaitsForASoundThatNeverEndsNoLongerThanItsBound) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 3);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 100, -20);  // a jammer starts, and plays on
  const double asked = t;
  while (air.start_at(sense, t, AirUse::Stop) > t) t = hear_for(sense, t, kBlockMs, -20);
  EXPECT_GE(t - asked, kMaxStopWaitMs);
  EXPECT_LT(t - asked, kMaxStopWaitMs + 2 * kBlockMs);
  air.started(sense, t);
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t + kQuietMs) << "a command does wait for it";
}

TEST(AirAccess, InASharedRoomALongRunYieldsForLongerThanTheOthersWait) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 5);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);  // another was heard: the room is shared
  t = wait_for_air(sense, air, t, AirUse::Command);
  const double run_start = t;
  while (air.start_at(sense, t, AirUse::Command) == t) t = exchange(sense, air, t, 250);
  EXPECT_GE(t - run_start, kMaxHoldMs);
  EXPECT_LT(t - run_start, kMaxHoldMs + 250 + kBlockMs);
  EXPECT_EQ(air.yields(), 1u);
  // The pause outlasts another waiting sender's quiet hold and its longest backoff.
  const double resume = wait_for_air(sense, air, t, AirUse::Command);
  EXPECT_GT(resume - t, kQuietMs + (kBackoffSlots - 1) * kSlotMs + kSlotMs);
  // Nobody took the air: a new run, as long, begins after the pause.
  t = exchange(sense, air, resume, 250);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Command), t) << "the new run was taken for the old";
  EXPECT_EQ(air.yields(), 1u);
}

TEST(AirAccess, AnotherHeardDuringTheYieldKeepsTheAir) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 5);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);
  t = wait_for_air(sense, air, t, AirUse::Command);
  while (air.start_at(sense, t, AirUse::Command) == t) t = exchange(sense, air, t, 250);
  t = hear_for(sense, t, kOwnLatencyMs + kQuietMs, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);  // the other took the air in our pause
  EXPECT_GE(air.start_at(sense, t, AirUse::Command), t + kQuietMs);
}

TEST(AirAccess, AStarvedSenderWaitsOnlyAShortQuietAndAShortBackoff) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 9);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  const double from = t;
  // Another that never heard us holds the air: 250 ms frames, 50 ms apart.
  while (t - from < kMaxDeferMs + 500) {
    t = hear_for(sense, t, 250, -20);
    ASSERT_GT(air.start_at(sense, t, AirUse::Command), t);
    t = hear_for(sense, t, 50, kNoiseDbfs);
  }
  EXPECT_EQ(air.deferred(), 1u);
  // Its listening pause: we start within a slot's quiet and our starved backoff.
  const double last_busy = *sense.last_busy_ms();
  const double at = air.start_at(sense, t, AirUse::Command);
  EXPECT_GE(at, last_busy + kStarvedQuietMs);
  EXPECT_LE(at, last_busy + kStarvedQuietMs + (kStarvedSlots - 1) * kSlotMs);
  EXPECT_LT(at - last_busy, kListenWindowMs) << "it would start after the other's listening pause";
}

// A yielding sender whose other never heard it (their frames overlapped, each hid the other's
// under its own) waits for a quiet the other never leaves: it pauses only to listen. After
// kMaxDeferMs it starts in that listening pause. (bench.FleetLoad once saw a server wait
// 29 s so, while the other's driver sent frames back to back.)
TEST(AirAccess, AYieldingSenderStartsInTheListeningPauseOfAnotherThatNeverHeardIt) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 5);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 200, -20);  // another was heard: the room is shared
  t = wait_for_air(sense, air, t, AirUse::Command);
  while (air.start_at(sense, t, AirUse::Command) == t) t = exchange(sense, air, t, 250);
  ASSERT_EQ(air.yields(), 1u);
  // The other holds the air, 250 ms frames 20 ms apart, and then pauses to listen.
  const double from = t;
  while (t - from < kMaxDeferMs + 500) {
    t = hear_for(sense, t, 250, -20);
    ASSERT_GT(air.start_at(sense, t, AirUse::Command), t);
    t = hear_for(sense, t, 20, kNoiseDbfs);
  }
  const double pause_end = t + kOwnLatencyMs + kListenWindowMs;
  const double at = wait_for_air(sense, air, t, AirUse::Command);
  EXPECT_LT(at, pause_end) << "it waited past the other's listening pause";
}

TEST(AirAccess, AfterALossInASharedRoomItBacksOffAtRandomAloneItDoesNot) {
  std::set<double> waits;
  for (std::uint64_t seed = 0; seed < 32; ++seed) {
    CarrierSense sense;
    AirAccess air(kQuietMs, seed);
    double t = hear_for(sense, 0, 1000, kNoiseDbfs);
    t = hear_for(sense, t, 200, -20);
    t = wait_for_air(sense, air, t, AirUse::Command);
    t = exchange(sense, air, t, 250);
    air.unanswered(sense, t);
    waits.insert(air.start_at(sense, t, AirUse::Command) - t);
  }
  EXPECT_GT(waits.size(), 8u);
  EXPECT_LE(*waits.rbegin(), (kLossSlots - 1) * kSlotMs);

  CarrierSense sense;
  AirAccess air(kQuietMs, 1);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = exchange(sense, air, t, 250);
  air.unanswered(sense, t);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Command), t) << "a lone sender's retransmission waited";
}

// Two senders that started together and then send back to back: each one's frames sound under
// the other's exchanges, where a microphone takes every sound for its own, so neither ever
// hears the air busy, and they stay in step until a listening pause 20 s on (three senders on
// the PulseAudio air: 102 of 562 frames started within 100 ms of another's). An answer of the
// other's robot read under our exchange ends that: the next frame defers until the air has
// been heard quiet for the whole hold, and the room now shared, our 3 s run yields.
TEST(AirAccess, AnAnswerOfAnothersRobotReadUnderOurExchangeEndsTwoSendersInStep) {
  CarrierSense sense;
  AirAccess air(kQuietMs, 1);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  for (int k = 0; k < 20; ++k) {
    ASSERT_EQ(air.start_at(sense, t, AirUse::Command), t) << "frame " << k;
    t = exchange(sense, air, t, 150);  // ours and the other's frames, one sound
  }
  EXPECT_EQ(air.deferred(), 0u);
  air.started(sense, t);
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.answer_masked(t - 40);
  sense.own_end(t);
  EXPECT_GT(air.start_at(sense, t, AirUse::Command), t);
  EXPECT_EQ(air.deferred(), 1u);
  const double start = wait_for_air(sense, air, t, AirUse::Command);
  EXPECT_GE(start - t, kQuietMs) << "it started before the air was heard quiet for the hold";
  EXPECT_EQ(air.yields(), 1u);
  EXPECT_LE(start - t, kOwnLatencyMs + kQuietMs + (kBackoffSlots + 2) * kSlotMs + 2 * kBlockMs);
}
