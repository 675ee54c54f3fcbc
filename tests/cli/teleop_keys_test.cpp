// dtmfctl teleop's keys: turtlebot3_teleop_key's steps, reverse, stop and the robot's limits.
#include <gtest/gtest.h>

#include "teleop_keys.h"

using namespace dtmf;
using dtmf::cli::apply_key;
using dtmf::cli::KeyEffect;
using dtmf::cli::TeleopTarget;

TEST(TeleopKeys, StepLikeTurtlebot3TeleopAndReverse) {
  TeleopTarget t;
  EXPECT_EQ(apply_key('w', t, command::burger()), KeyEffect::Changed);
  EXPECT_EQ(apply_key('w', t, command::burger()), KeyEffect::Changed);
  EXPECT_DOUBLE_EQ(t.linear_mps, 0.02);
  for (int k = 0; k < 5; ++k) apply_key('x', t, command::burger());
  EXPECT_DOUBLE_EQ(t.linear_mps, -0.03) << "x past zero reverses";
  apply_key('a', t, command::burger());
  apply_key('a', t, command::burger());
  apply_key('d', t, command::burger());
  EXPECT_DOUBLE_EQ(t.angular_radps, 0.1);
  EXPECT_EQ(apply_key(' ', t, command::burger()), KeyEffect::Changed);
  EXPECT_EQ(t, TeleopTarget{});
  EXPECT_EQ(apply_key('s', t, command::burger()), KeyEffect::None) << "already still";
  EXPECT_EQ(apply_key('q', t, command::burger()), KeyEffect::Quit);
  EXPECT_EQ(apply_key(3, t, command::burger()), KeyEffect::Quit);
  EXPECT_EQ(apply_key('z', t, command::burger()), KeyEffect::None);
}

TEST(TeleopKeys, StepsStopAtTheModelsLimitsExactly) {
  TeleopTarget t;
  for (int k = 0; k < 40; ++k) apply_key('w', t, command::burger());
  EXPECT_DOUBLE_EQ(t.linear_mps, 0.22);
  EXPECT_EQ(apply_key('w', t, command::burger()), KeyEffect::None);
  for (int k = 0; k < 40; ++k) apply_key('d', t, command::waffle());
  EXPECT_DOUBLE_EQ(t.angular_radps, -1.82);
  // The target is always one a Velocity command accepts.
  EXPECT_NO_THROW(command::velocity_command(command::burger(), t.linear_mps, -1.82, 1.0));
}

TEST(TeleopKeys, EStopsEveryRobotEvenWhenThisOneStandsStill) {
  TeleopTarget t;
  apply_key('w', t, command::burger());
  EXPECT_EQ(apply_key('e', t, command::burger()), KeyEffect::StopEveryRobot);
  EXPECT_EQ(t, TeleopTarget{});
  EXPECT_EQ(apply_key('E', t, command::burger()), KeyEffect::StopEveryRobot) << "others may still move";
}
