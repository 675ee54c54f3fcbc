// Robot application layer: the velocity provider's states, scaling and safety stops.
#include <gtest/gtest.h>

#include "velocity_provider.h"

#include <cmath>

using namespace dtmf;
using namespace dtmf::agent;
using dtmf::command::burger;
using dtmf::command::robot_model_by_name;
using dtmf::command::waffle;

TEST(VelocityProvider, StartsIdleAndStill) {
  VelocityProvider p(burger(), 30);
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.update(0), Velocity{});
}

TEST(VelocityProvider, DriveForDurationMovesThenStopsAtItsEndTime) {
  VelocityProvider p(burger(), 30);
  p.apply(command::DriveForDuration{50, 2}, 10.0);
  EXPECT_EQ(p.state(), MotionState::Duration);
  EXPECT_DOUBLE_EQ(p.update(10.0).linear_mps, 0.11);
  EXPECT_DOUBLE_EQ(p.update(11.99).linear_mps, 0.11);
  EXPECT_DOUBLE_EQ(p.update(11.99).angular_radps, 0.0);
  EXPECT_EQ(p.update(12.0), Velocity{});
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.take_stop_reason(), "duration ended");
  EXPECT_FALSE(p.take_stop_reason());
}

TEST(VelocityProvider, TurnsScaleToTheModelsTurnRateBothWays) {
  VelocityProvider p(burger(), 30);
  p.apply(command::TurnForDuration{-100, 1}, 0);
  EXPECT_DOUBLE_EQ(p.update(0.5).angular_radps, -2.84);
  EXPECT_DOUBLE_EQ(p.update(0.5).linear_mps, 0.0);
  p.apply(command::Turn{25}, 2);
  EXPECT_EQ(p.state(), MotionState::Continuous);
  EXPECT_DOUBLE_EQ(p.update(3).angular_radps, 0.71);
}

TEST(VelocityProvider, WaffleHasItsOwnLimits) {
  VelocityProvider p(waffle(), 30);
  p.apply(command::DriveForward{100}, 0);
  EXPECT_DOUBLE_EQ(p.update(1).linear_mps, 0.26);
  p.apply(command::Turn{100}, 1);
  EXPECT_DOUBLE_EQ(p.update(2).angular_radps, 1.82);
  EXPECT_THROW(robot_model_by_name("roomba"), std::invalid_argument);
  EXPECT_EQ(robot_model_by_name("waffle_pi").name, "waffle");
}

TEST(VelocityProvider, ContinuousMotionStopsAtTheSafetyLimit) {
  VelocityProvider p(burger(), 30);
  p.apply(command::DriveForward{40}, 100);
  EXPECT_DOUBLE_EQ(p.update(129.9).linear_mps, 0.088);
  EXPECT_EQ(p.update(130), Velocity{});
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_NE(p.take_stop_reason()->find("30 s safety limit"), std::string::npos);
}

TEST(VelocityProvider, ALimitOfZeroNeverStops) {
  VelocityProvider p(burger(), 0);
  p.apply(command::Turn{-10}, 0);
  EXPECT_NEAR(p.update(86400).angular_radps, -0.284, 1e-12);
  EXPECT_EQ(p.state(), MotionState::Continuous);
}

TEST(VelocityProvider, StopStopsAtOnceAndResetChangesNothing) {
  VelocityProvider p(burger(), 30);
  p.apply(command::DriveForward{100}, 0);
  p.apply(command::Reset{}, 1);
  EXPECT_DOUBLE_EQ(p.update(1).linear_mps, 0.22);
  p.apply(command::Stop{}, 2);
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.update(2), Velocity{});
}

TEST(VelocityProvider, ANewCommandReplacesTheRunningOne) {
  VelocityProvider p(burger(), 30);
  p.apply(command::DriveForDuration{100, 8}, 0);
  p.apply(command::TurnForDuration{50, 1}, 1);
  const Velocity v = p.update(1.5);
  EXPECT_DOUBLE_EQ(v.linear_mps, 0.0);
  EXPECT_DOUBLE_EQ(v.angular_radps, 1.42);
  EXPECT_EQ(p.update(2.0), Velocity{});  // the turn's end, not the drive's
}

TEST(VelocityProvider, AVelocityRampsAtTheAccelerationLimitsAndHoldsForItsLease) {
  VelocityProvider p(burger(), 30);
  p.update(0);
  p.apply(command::Velocity{0.5, -0.5, 1.0}, 0);  // 0.11 m/s, -1.42 rad/s
  EXPECT_EQ(p.state(), MotionState::Leased);
  // 2.5 m/s² and 25 rad/s²: after 20 ms, 0.05 m/s and -0.5 rad/s.
  EXPECT_NEAR(p.update(0.02).linear_mps, 0.05, 1e-9);
  EXPECT_NEAR(p.update(0.02).angular_radps, -0.5, 1e-9);
  EXPECT_NEAR(p.update(0.1).linear_mps, 0.11, 1e-9);
  EXPECT_NEAR(p.update(0.1).angular_radps, -1.42, 1e-9);
  EXPECT_NEAR(p.update(0.94).linear_mps, 0.11, 1e-9) << "held within the lease";
  EXPECT_EQ(p.state(), MotionState::Leased);
  EXPECT_TRUE(p.changing_by_itself());
  // The lease ends at 1.0 s and the wheels stand still then: the turn takes longest to
  // stop, 1.42 / 25 = 56.8 ms, so the ramp down begins at 0.9432 s.
  const Velocity after = p.update(0.97);
  EXPECT_NEAR(after.linear_mps, 0.11 - 2.5 * (0.97 - 0.9432), 1e-9);
  EXPECT_NEAR(after.angular_radps, -1.42 + 25 * (0.97 - 0.9432), 1e-9);
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.take_stop_reason(), "lease ended");
  EXPECT_EQ(p.update(1.0), Velocity{}) << "zero at the lease's end, exactly";
  EXPECT_FALSE(p.changing_by_itself());
  EXPECT_FALSE(p.settles_at_s()) << "standing still";
}

TEST(VelocityProvider, SaysWhenTheWheelsSettleSoTheAgentPublishesThen) {
  VelocityProvider p(burger(), 30);
  p.update(0);
  EXPECT_FALSE(p.settles_at_s());
  p.apply(command::Velocity{0.5, -0.5, 1.0}, 0.2);
  // The turn takes longest to reach: 1.42 / 25 = 56.8 ms after the frame was heard.
  ASSERT_TRUE(p.settles_at_s());
  EXPECT_NEAR(*p.settles_at_s(), 0.2568, 1e-9);
  EXPECT_EQ(p.update(0.2568), (Velocity{0.11, -1.42})) << "exactly the target then";
  EXPECT_DOUBLE_EQ(*p.settles_at_s(), 1.2) << "next: standing still at the lease's end";
  p.apply(command::DriveForward{50}, 0.5);
  EXPECT_FALSE(p.settles_at_s()) << "a seed command holds with no end set here";
}

TEST(VelocityProvider, ARenewalExtendsTheLeaseAndAReversalNeverJerks) {
  VelocityProvider p(burger(), 30);
  p.update(0);
  p.apply(command::Velocity{1, 0, 0.5}, 0);
  p.update(0.2);
  p.apply(command::Velocity{-1, 0, 0.5}, 0.4);  // renewal and reversal
  double last = p.update(0.4).linear_mps;
  EXPECT_NEAR(last, 0.22, 1e-9);
  for (double t = 0.45; t <= 0.81; t += 0.05) {  // the publish cycle of 20 Hz, until the ramp down
    const double now = p.update(t).linear_mps;
    EXPECT_LE(std::abs(now - last), 2.5 * 0.05 + 1e-9) << "at " << t << " s";
    last = now;
  }
  EXPECT_NEAR(last, -0.22, 1e-9) << "reached the reversed velocity within the renewed lease";
  EXPECT_EQ(p.state(), MotionState::Leased);
  EXPECT_EQ(p.update(0.9), Velocity{}) << "stopped at 0.4 + 0.5 s";
  EXPECT_EQ(p.state(), MotionState::Idle);
}

TEST(VelocityProvider, StopAndTheSeedsCommandsTakeEffectAtOnceEvenWhileRamping) {
  VelocityProvider p(burger(), 30);
  p.update(0);
  p.apply(command::Velocity{1, 1, 2}, 0);
  p.update(0.05);
  p.apply(command::Stop{}, 0.06);
  EXPECT_EQ(p.update(0.06), Velocity{});
  EXPECT_FALSE(p.changing_by_itself());
  p.apply(command::Velocity{1, 0, 2}, 0.1);
  p.update(0.12);
  p.apply(command::DriveForward{50}, 0.13);
  EXPECT_DOUBLE_EQ(p.update(0.13).linear_mps, 0.11);
  EXPECT_EQ(p.state(), MotionState::Continuous);
}

TEST(VelocityProvider, TheLeaseRunsFromTheFramesStartNotFromWhenItWasHeard) {
  VelocityProvider p(burger(), 30);
  p.update(0);
  p.apply(command::Velocity{1, 1, 0.5}, 0.15, 0.0);  // a 150 ms frame, heard at its end
  p.update(0.38);
  EXPECT_EQ(p.state(), MotionState::Leased);
  // From both top speeds the turn takes 2.84 / 25 = 0.114 s to stop, so the ramp down
  // begins at 0.386 s and the wheels stand still at 0.0 + 0.5 s, not at 0.15 + 0.5 s.
  EXPECT_NE(p.update(0.45), Velocity{});
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.update(0.5), Velocity{});
}
