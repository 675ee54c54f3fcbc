// When the bridge opens, writes, closes and holds a robot's Teleop stream.
#include "teleop_plan.h"

#include <gtest/gtest.h>

namespace dtmf::ros_bridge {
namespace {

using Kind = PlanCall::Kind;
const Twist kForward{0.1, 0};
const Twist kLeft{0.1, 0.5};
const Twist kZero{};
constexpr double kLeaseMs = 1000;

TEST(TeleopPlan, OpensOnTheFirstVelocityWritesChangesAndRepeatsTheSameEveryHalfSecond) {
  TeleopPlan plan(kLeaseMs);
  EXPECT_FALSE(plan.step(kZero, 0)) << "nothing to drive: no stream";
  EXPECT_EQ(plan.step(kForward, 10), (PlanCall{Kind::Open, kForward}));
  EXPECT_FALSE(plan.step(kForward, 20));
  EXPECT_EQ(plan.step(kLeft, 30), (PlanCall{Kind::Write, kLeft}));
  ASSERT_TRUE(plan.next_deadline_ms());
  EXPECT_DOUBLE_EQ(*plan.next_deadline_ms(), 30 + TeleopPlan::kRepeatMs);
  EXPECT_FALSE(plan.step(kLeft, 529));
  EXPECT_EQ(plan.step(kLeft, 530), (PlanCall{Kind::Write, kLeft})) << "the server ends a stream silent for 1 s";
}

TEST(TeleopPlan, AZeroIsWrittenAtOnceAndTheStreamClosesWhenTheRobotConfirmsIt) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  EXPECT_EQ(plan.step(kZero, 100), (PlanCall{Kind::Write, kZero}));
  EXPECT_EQ(plan.state(), StreamState::Stopping);
  EXPECT_FALSE(plan.step(kZero, 150));
  plan.on_confirmed(kZero);
  EXPECT_EQ(plan.step(kZero, 200), (PlanCall{Kind::Close, {}}));
  EXPECT_EQ(plan.state(), StreamState::Closing);
  EXPECT_FALSE(plan.step(kForward, 210)) << "no second stream before the first has ended";
  plan.on_stream_end(StreamEnd::Finished, 300);
  EXPECT_EQ(plan.step(kForward, 300), (PlanCall{Kind::Open, kForward}));
}

TEST(TeleopPlan, AnUnconfirmedZeroIsRenewedThenClosedAfterALease) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  plan.step(kZero, 100);
  EXPECT_EQ(plan.step(kZero, 600), (PlanCall{Kind::Write, kZero})) << "renewed: the stream must live";
  EXPECT_FALSE(plan.step(kZero, 1099));
  EXPECT_EQ(plan.step(kZero, 1100), (PlanCall{Kind::Close, {}})) << "a lease after the zero: stopped either way";
}

TEST(TeleopPlan, AVelocityWhileStoppingDrivesAgainOnTheSameStream) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  plan.step(kZero, 100);
  EXPECT_EQ(plan.step(kLeft, 150), (PlanCall{Kind::Write, kLeft}));
  EXPECT_EQ(plan.state(), StreamState::Open);
}

TEST(TeleopPlan, AfterAStopItHoldsUntilTheInputIsZero) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  plan.on_stream_end(StreamEnd::Stopped, 100);
  EXPECT_EQ(plan.state(), StreamState::Held);
  for (double t = 100; t < 5000; t += 50) ASSERT_FALSE(plan.step(kForward, t)) << "Nav2 at 20 Hz must not undo a stop";
  EXPECT_FALSE(plan.next_deadline_ms());
  EXPECT_FALSE(plan.step(kZero, 5000));
  EXPECT_EQ(plan.state(), StreamState::Closed);
  EXPECT_EQ(plan.step(kForward, 5050), (PlanCall{Kind::Open, kForward}));
}

TEST(TeleopPlan, AFailedStreamIsTriedAgainAfterASecondWhileTheInputAsks) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  plan.on_stream_end(StreamEnd::Failed, 100);
  EXPECT_FALSE(plan.step(kForward, 1099));
  ASSERT_TRUE(plan.next_deadline_ms());
  EXPECT_DOUBLE_EQ(*plan.next_deadline_ms(), 1100);
  EXPECT_EQ(plan.step(kForward, 1100), (PlanCall{Kind::Open, kForward}));
}

TEST(TeleopPlan, APastRetryIsForgottenSoNoDeadlineStaysBehind) {
  TeleopPlan plan(kLeaseMs);
  plan.step(kForward, 0);
  plan.on_stream_end(StreamEnd::Failed, 100);
  EXPECT_FALSE(plan.step(kZero, 2000));
  EXPECT_FALSE(plan.next_deadline_ms()) << "a deadline in the past would wake the loop for nothing, forever";
}

}  // namespace
}  // namespace dtmf::ros_bridge
