// How long the air may hold a command (issue 59): kMaxDeferToUnknownMs, its frames' and
// retransmissions' waits together. A jammer that leaves a short quiet every few seconds kept
// the room's floor down and held a command for good (a steady sound, until the floor took it
// in: up to 30 s); a quiet in the jam renews nothing now. A stop keeps its own 400 ms, a stop
// for every robot never waits, and another real sender's exchanges are deferred to as before.
#include <gtest/gtest.h>

#include <cmath>

#include "profile/link_profile.h"
#include "reliability/air_access.h"
#include "reliability/heard_blocks.h"

using namespace dtmf::reliability;

namespace {

using dtmf::test_support::hear_for;
using dtmf::test_support::kBlockMs;
constexpr double kSeedQuietMs = 700;  // a sender that knows the seed's links
constexpr double kNoiseDbfs = -60;
constexpr double kJamDbfs = -20;
constexpr double kJamSoundMs = 2000;  // the jammer sounds this long, then leaves ...
constexpr double kJamQuietMs = 100;   // ... this much quiet: shorter than any hold, and the floor stays down
constexpr double kLongMs = 60'000;    // longer than any bound; the jammer's patience

// The jammer from `t`, heard block by block, until `air` lets a frame of `use` start or
// `limit_ms` has passed; when that was.
double jam_until_start(CarrierSense& sense, AirAccess& air, AirWait& wait, double t, AirUse use,
                       double limit_ms = kLongMs) {
  const double from = t;
  for (; t - from < limit_ms; t += kBlockMs) {
    if (air.start_at(sense, t, use, wait) <= t) return t;
    const bool quiet = std::fmod(t - from, kJamSoundMs + kJamQuietMs) >= kJamSoundMs;
    sense.hear(quiet ? kNoiseDbfs : kJamDbfs, t + kBlockMs);
  }
  return t;
}

// Our frame's exchange from `at_ms`, `ms` of our own sound; returns its end.
double exchange(CarrierSense& sense, AirAccess& air, AirWait& wait, double at_ms, double ms) {
  air.started(sense, at_ms, wait);
  sense.own_begin(at_ms);
  const double end = hear_for(sense, at_ms, ms, -10);
  sense.own_end(end);
  return end;
}

}  // namespace

// Each figure from the rules it stands on: one deferral to a sender of this software that
// has heard us, twice.
TEST(AirWaitBound, TheBoundFollowsFromTheRulesAndEveryProfilesExchange) {
  EXPECT_DOUBLE_EQ(kStarvedDeferralMs, 4350);
  EXPECT_DOUBLE_EQ(kMaxDeferToUnknownMs, 8700);
  EXPECT_LT(kMaxDeferToUnknownMs, kFloorWindowMs) << "shorter than what a steady sound held a command before";
  for (const dtmf::LinkProfile* p : dtmf::all_profiles()) {
    // Another's run in a shared room: kMaxHoldMs and the exchange under way (its frame, the
    // wait for its answer, the answer). It must end before a deferral starves, so that the
    // starved start falls in that sender's pause and not into its exchange.
    const double exchange_ms = p->timing.ack_timeout_ms + p->timing.ack_ms;
    EXPECT_LT(kMaxHoldMs + exchange_ms + kOwnLatencyMs, kMaxDeferMs) << p->name;
  }
}

TEST(AirWaitBound, ASoundThatLeavesShortQuietsHoldsACommandNoLongerThanTheBound) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 3);
  AirWait wait;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  const double asked = hear_for(sense, t, 100, kJamDbfs);  // the jammer has begun
  const double start = jam_until_start(sense, air, wait, asked, AirUse::Command);
  ASSERT_LT(start - asked, kLongMs) << "the jammer held the command for good";
  EXPECT_GE(start - asked, kMaxDeferToUnknownMs) << "it gave up before the bound";
  EXPECT_LE(start - asked, kMaxDeferToUnknownMs + kBlockMs);
  EXPECT_EQ(air.deferred(), 1u);
  EXPECT_EQ(wait.reason.cause, AirWaitCause::Sound);
  EXPECT_NEAR(wait.reason.over_floor_db, kJamDbfs - kNoiseDbfs, 1);
  EXPECT_EQ(air_wait_text(wait.reason), "sound 40 dB over the room's floor");

  // Its retransmission, and any later frame of the command, go at once into the jam.
  t = exchange(sense, air, wait, start, 250);
  EXPECT_DOUBLE_EQ(wait.held_ms, start - asked);
  EXPECT_EQ(wait.waits, 1);
  t = hear_for(sense, t, 300, kJamDbfs);
  EXPECT_EQ(air.start_at(sense, t, AirUse::Command, wait), t) << "the spent bound was renewed";
  exchange(sense, air, wait, t, 250);
  EXPECT_EQ(wait.waits, 1);
  EXPECT_DOUBLE_EQ(wait.held_ms, start - asked);
}

// The bound is the command's, not each frame's: what its first frame waited is gone for the next.
TEST(AirWaitBound, ACommandsFramesShareOneBound) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 4);
  AirWait wait;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 100, kJamDbfs);
  const double asked = t;
  // Its first frame: 5 s of sound, then the air is free.
  while (air.start_at(sense, t, AirUse::Command, wait) > t) {
    sense.hear(t - asked < 5000 ? kJamDbfs : kNoiseDbfs, t + kBlockMs);
    t += kBlockMs;
  }
  t = exchange(sense, air, wait, t, 250);
  const double first_ms = wait.held_ms;
  EXPECT_GE(first_ms, 5000);
  EXPECT_LT(first_ms, kMaxDeferToUnknownMs);
  // Its second: the jammer, for good.
  t = hear_for(sense, t, 100, kJamDbfs);
  const double second = jam_until_start(sense, air, wait, t, AirUse::Command);
  EXPECT_LE(second - t, kMaxDeferToUnknownMs - first_ms + kBlockMs);
  EXPECT_GE(second - t, kMaxDeferToUnknownMs - first_ms - kBlockMs);
  air.started(sense, second, wait);
  EXPECT_LE(wait.held_ms, kMaxDeferToUnknownMs + kBlockMs);
  EXPECT_GT(second, asked);
}

TEST(AirWaitBound, AStopWaitsAtMostItsOwnBoundAndAStopForEveryRobotNeverWaits) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 5);
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 100, kJamDbfs);
  AirWait stop;
  const double stop_at = jam_until_start(sense, air, stop, t, AirUse::Stop);
  EXPECT_GE(stop_at - t, kMaxStopWaitMs);
  EXPECT_LE(stop_at - t, kMaxStopWaitMs + kBlockMs);
  t = exchange(sense, air, stop, stop_at, 250);
  EXPECT_EQ(stop.reason.cause, AirWaitCause::Sound);

  t = hear_for(sense, t, 300, kJamDbfs);
  AirWait every_robot;
  EXPECT_EQ(air.start_at(sense, t, AirUse::EveryRobotStop, every_robot), t);
  air.started(sense, t, every_robot);
  EXPECT_EQ(every_robot.waits, 0);
  EXPECT_DOUBLE_EQ(every_robot.held_ms, 0);
}

// Another sender that has heard us (the room is shared): a run of two seed exchanges (a chord
// of 800 ms, 650 ms of silence, a 300 ms answer), then its yield pause of 1.2 s. We wait for
// all of it, never start into it, and start in its pause, well within the bound.
TEST(AirWaitBound, ARealSendersExchangesAreStillDeferredTo) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 6);
  AirWait wait;
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  const double run_from = t;
  constexpr double kExchangeMs = 800 + 650 + 300, kRunMs = 2 * kExchangeMs, kPauseMs = 1200;
  const auto others = [&](double at_ms) {
    const double in_run = at_ms - run_from;
    if (in_run >= kRunMs) return kNoiseDbfs;
    const double in_exchange = std::fmod(in_run, kExchangeMs);
    return in_exchange < 800 ? -20.0 : in_exchange < 1450 ? kNoiseDbfs : -25.0;
  };
  t = hear_for(sense, t, 100, -20);  // its frame began: we are asked to send now
  const double asked = t;
  while (air.start_at(sense, t, AirUse::Command, wait) > t) {
    sense.hear(others(t), t + kBlockMs);
    t += kBlockMs;
    ASSERT_LT(t - asked, kLongMs);
  }
  EXPECT_GE(t, run_from + kRunMs + kStarvedQuietMs) << "it started into the other's exchange";
  EXPECT_LT(t, run_from + kRunMs + kPauseMs) << "it missed the other's pause";
  EXPECT_LT(t - asked, kMaxDeferToUnknownMs);
  EXPECT_EQ(wait.reason.cause, AirWaitCause::Sound);
  EXPECT_EQ(air.deferred(), 1u);
}

// What the operator is told for each of the sender's own rules.
TEST(AirWaitBound, AWaitSaysWhy) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 7);
  double t = hear_for(sense, 0, 500, kNoiseDbfs);
  // Alone, after kListenEveryMs of frames back to back: a listening pause.
  AirWait wait;
  while (air.start_at(sense, t, AirUse::Command, wait) <= t) {
    wait = {};
    t = exchange(sense, air, wait, t, 250);
  }
  EXPECT_EQ(wait.reason.cause, AirWaitCause::Listen);
  EXPECT_EQ(air_wait_text(wait.reason), "listening for another sender that may be waiting");
  EXPECT_EQ(air_wait_text({AirWaitCause::Yield}), "yielding to another sender");
  EXPECT_EQ(air_wait_text({AirWaitCause::AnsweredExchange}),
            "another sender's exchange (its robot's answer was heard)");
  EXPECT_EQ(air_wait_text({AirWaitCause::None}), "");
}

// A sender that never heard us sends back to back and pauses to listen only every
// kListenEveryMs: the bound sends our command into its run, and the next command, whose wait
// goes on under the same sound, starts starved, in that sender's listening pause (where it is
// heard), as a sender that had waited all along would (AirAccess's
// AYieldingSenderStartsInTheListeningPauseOfAnotherThatNeverHeardIt).
TEST(AirWaitBound, AfterTheBoundTheNextCommandStillMeetsASenderThatNeverHeardUsInItsListeningPause) {
  CarrierSense sense;
  AirAccess air(kSeedQuietMs, 8);
  // The other's run: exchanges of 170 ms, 30 ms apart (a quiet shorter than any hold).
  const auto others_run = [](double at_ms) { return std::fmod(at_ms, 200) < 170 ? -20.0 : kNoiseDbfs; };
  double t = hear_for(sense, 0, 1000, kNoiseDbfs);
  t = hear_for(sense, t, 100, -20);  // its run has begun
  AirWait first;
  const double asked = t;
  while (air.start_at(sense, t, AirUse::Command, first) > t) {
    sense.hear(others_run(t), t + kBlockMs);
    t += kBlockMs;
    ASSERT_LT(t - asked, kLongMs) << "the other's run held the command for good";
  }
  air.started(sense, t, first);
  EXPECT_DOUBLE_EQ(first.held_ms, kMaxDeferToUnknownMs);
  sense.own_begin(t);
  t = hear_for(sense, t, 150, -10);
  sense.own_end(t);
  // The next command asks while the other's run goes on for 2 s more; then its pause.
  AirWait second;
  const double pause_from = t + 2000;
  while (air.start_at(sense, t, AirUse::Command, second) > t) {
    sense.hear(t < pause_from ? others_run(t) : kNoiseDbfs, t + kBlockMs);
    t += kBlockMs;
    ASSERT_LT(t, pause_from + kOwnLatencyMs + kListenWindowMs) << "it missed the other's listening pause";
  }
  EXPECT_GE(t, pause_from + kStarvedQuietMs) << "it started into the other's run";
  air.started(sense, t, second);
  EXPECT_LT(second.held_ms, kMaxDeferToUnknownMs) << "the air, not the bound, let it go";
}
