// The teleop stream's rules, as pure state: the newest target only, lease renewal, silence,
// and the link's quality.
#include <gtest/gtest.h>

#include "teleop_session.h"

using namespace dtmf;
using dtmf::server::TeleopSession;

namespace {
command::Velocity v(double linear, double lease_s = 1.0) { return {linear, 0, lease_s}; }
}  // namespace

TEST(TeleopSession, SendsOnlyTheNewestTargetAndNothingBeforeOne) {
  TeleopSession s(command::burger());
  EXPECT_FALSE(s.frame_due(0.0));
  s.set_target(v(0.1), 0.0);
  ASSERT_TRUE(s.frame_due(0.0));
  EXPECT_FALSE(s.frame_due(0.01)) << "already sent";
  // Three key presses while that frame is on air: only the last is sent.
  s.set_target(v(0.2), 0.05);
  s.set_target(v(0.3), 0.10);
  s.set_target(v(0.4), 0.15);
  s.frame_ended(0.2, true, v(0.1), 120);
  const auto next = s.frame_due(0.2);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->linear_fraction, 0.4);
}

TEST(TeleopSession, RenewsTheLeaseAtHalfOfItAndResendsAnUnconfirmedFrameAtOnce) {
  TeleopSession s(command::burger());
  s.set_target(v(0.5, 1.0), 0.0);
  ASSERT_TRUE(s.frame_due(0.0));
  s.frame_ended(0.25, true, v(0.5, 1.0), 120);
  s.set_target(v(0.5, 1.0), 0.3);  // the client repeats its target
  EXPECT_FALSE(s.frame_due(0.3)) << "the same target, lease still fresh";
  s.set_target(v(0.5, 1.0), 0.45);
  EXPECT_TRUE(s.frame_due(0.5)) << "half the lease has passed";
  s.frame_ended(0.75, false, std::nullopt, 0);  // lost
  EXPECT_TRUE(s.frame_due(0.75)) << "not confirmed: sent again now, not at the next renewal";
}

TEST(TeleopSession, ASilentClientEndedStreamOrStopSendsNothingMore) {
  TeleopSession silent(command::burger());
  silent.set_target(v(0.5), 0.0);
  ASSERT_TRUE(silent.frame_due(0.0));
  silent.frame_ended(0.2, true, v(0.5), 100);
  EXPECT_FALSE(silent.frame_due(1.1)) << "the client said nothing for over a second: the lease lapses";
  EXPECT_NEAR(silent.silent_s(1.1), 1.1, 1e-9);
  silent.set_target(v(0.5), 1.2);
  EXPECT_TRUE(silent.frame_due(1.2)) << "it speaks again";

  TeleopSession ended(command::burger());
  ended.set_target(v(0.5), 0.0);
  ended.end_stream();
  EXPECT_FALSE(ended.frame_due(0.0));
  EXPECT_TRUE(ended.stream_ended());

  TeleopSession halted(command::burger());
  halted.set_target(v(0.5), 0.0);
  halted.halt("a Stop call overtook");
  EXPECT_FALSE(halted.frame_due(0.0));
  EXPECT_EQ(halted.halted(), "a Stop call overtook");
}

TEST(TeleopSession, StatusReportsConfirmedVelocityLeaseLeftAndLinkQualityOverTheWindow) {
  TeleopSession s(command::burger());
  s.set_target({0.5, -0.25, 0.3}, 0.0);
  for (int k = 0; k < 4; ++k) {
    ASSERT_TRUE(s.frame_due(0.25 * k + 0.001)) << k;
    s.set_target({0.5, -0.25, 0.3}, 0.25 * k + 0.1);
    // Frames 0, 1, 3 answered; 3 of 4.
    s.frame_ended(0.25 * k + 0.2, k != 2, k != 2 ? std::optional(command::Velocity{0.5, -0.25, 0.3}) : std::nullopt,
                  110.0 + k);
  }
  auto status = s.status(1.0);
  EXPECT_DOUBLE_EQ(status.target_linear_mps, 0.11);
  EXPECT_DOUBLE_EQ(status.target_angular_radps, -0.71);
  ASSERT_TRUE(status.confirmed);
  EXPECT_DOUBLE_EQ(status.confirmed->linear_mps, 0.11);  // the same units as the target
  EXPECT_DOUBLE_EQ(status.confirmed->angular_radps, -0.71);
  EXPECT_DOUBLE_EQ(status.response_time_ms, 113.0);
  EXPECT_DOUBLE_EQ(status.link_quality, 0.75);
  EXPECT_EQ(status.frames_in_window, 4);
  EXPECT_NEAR(status.lease_left_s, 0.3 - (1.0 - 0.95), 1e-9);
  // Three seconds later the window is empty and the lease long gone.
  status = s.status(5.0);
  EXPECT_EQ(status.frames_in_window, 0);
  EXPECT_EQ(status.lease_left_s, 0.0);
}
