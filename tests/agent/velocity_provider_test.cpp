// Robot application layer: the velocity provider's states, scaling and safety stops.
#include <gtest/gtest.h>

#include "velocity_provider.h"

using namespace dtmf;
using namespace dtmf::agent;

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
  EXPECT_DOUBLE_EQ(p.update(11.99).angular_rps, 0.0);
  EXPECT_EQ(p.update(12.0), Velocity{});
  EXPECT_EQ(p.state(), MotionState::Idle);
  EXPECT_EQ(p.take_stop_reason(), "duration ended");
  EXPECT_FALSE(p.take_stop_reason());
}

TEST(VelocityProvider, TurnsScaleToTheModelsTurnRateBothWays) {
  VelocityProvider p(burger(), 30);
  p.apply(command::TurnForDuration{-100, 1}, 0);
  EXPECT_DOUBLE_EQ(p.update(0.5).angular_rps, -2.84);
  EXPECT_DOUBLE_EQ(p.update(0.5).linear_mps, 0.0);
  p.apply(command::Turn{25}, 2);
  EXPECT_EQ(p.state(), MotionState::Continuous);
  EXPECT_DOUBLE_EQ(p.update(3).angular_rps, 0.71);
}

TEST(VelocityProvider, WaffleHasItsOwnLimits) {
  VelocityProvider p(waffle(), 30);
  p.apply(command::DriveForward{100}, 0);
  EXPECT_DOUBLE_EQ(p.update(1).linear_mps, 0.26);
  p.apply(command::Turn{100}, 1);
  EXPECT_DOUBLE_EQ(p.update(2).angular_rps, 1.82);
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
  EXPECT_NEAR(p.update(86400).angular_rps, -0.284, 1e-12);
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
  EXPECT_DOUBLE_EQ(v.angular_rps, 1.42);
  EXPECT_EQ(p.update(2.0), Velocity{});  // the turn's end, not the drive's
}
