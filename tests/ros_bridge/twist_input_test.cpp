// The bridge's input as twist_mux keeps one: newest wins, a timeout, clamping, NaN dropped.
#include "twist_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dtmf::ros_bridge {
namespace {

const TwistLimits kBurger{0.22, 2.84};

TEST(TwistInput, TheNewestMessageWinsAndHoldsUntilItsTimeout) {
  TwistInput input(kBurger, 500);
  EXPECT_EQ(input.wanted(0), Twist{});
  input.take({0.1, 0.5}, 1000);
  input.take({0.2, -0.5}, 1100);
  EXPECT_EQ(input.wanted(1100), (Twist{0.2, -0.5}));
  EXPECT_EQ(input.wanted(1599), (Twist{0.2, -0.5}));
  EXPECT_EQ(input.wanted(1600), Twist{}) << "0.5 s after the last message the input is zero";
  EXPECT_EQ(input.taken(), 2);
}

TEST(TwistInput, SaysWhenTheNewestMessageExpiresUnlessItIsZeroOrPast) {
  TwistInput input(kBurger, 500);
  EXPECT_FALSE(input.expires_ms(0));
  input.take({0.1, 0}, 1000);
  ASSERT_TRUE(input.expires_ms(1200));
  EXPECT_DOUBLE_EQ(*input.expires_ms(1200), 1500);
  EXPECT_FALSE(input.expires_ms(1500));
  input.take({0, 0}, 1600);
  EXPECT_FALSE(input.expires_ms(1700)) << "a zero has nothing to time out";
}

TEST(TwistInput, ClampsToTheRobotsLimitsAndSaysSoOnce) {
  TwistInput input(kBurger, 500);
  const TakeResult first = input.take({1.0, -10.0}, 0);
  EXPECT_EQ(first.verdict, TwistVerdict::Clamped);
  EXPECT_TRUE(first.first_of_its_kind);
  EXPECT_EQ(input.wanted(0), (Twist{0.22, -2.84}));
  const TakeResult second = input.take({-5.0, 0}, 10);
  EXPECT_EQ(second.verdict, TwistVerdict::Clamped);
  EXPECT_FALSE(second.first_of_its_kind);
  EXPECT_EQ(input.wanted(10), (Twist{-0.22, 0}));
  EXPECT_EQ(input.take({0.1, 0.1}, 20).verdict, TwistVerdict::Taken);
}

TEST(TwistInput, DropsANaNOrInfiniteMessageKeepingTheLastGoodOneAndSaysSoOnce) {
  TwistInput input(kBurger, 500);
  input.take({0.1, 0.2}, 0);
  const TakeResult nan = input.take({std::nan(""), 0}, 10);
  EXPECT_EQ(nan.verdict, TwistVerdict::NotFinite);
  EXPECT_TRUE(nan.first_of_its_kind);
  const TakeResult inf = input.take({0, std::numeric_limits<double>::infinity()}, 20);
  EXPECT_EQ(inf.verdict, TwistVerdict::NotFinite);
  EXPECT_FALSE(inf.first_of_its_kind);
  EXPECT_EQ(input.wanted(20), (Twist{0.1, 0.2}));
  EXPECT_EQ(input.wanted(500), Twist{}) << "a dropped message does not renew the timeout";
  EXPECT_EQ(input.taken(), 1);
}

}  // namespace
}  // namespace dtmf::ros_bridge
