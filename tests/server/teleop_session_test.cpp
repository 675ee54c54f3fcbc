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

TEST(TeleopSession, RenewedJointlyItSendsChangesChecksAndOnlyLateRenewalsOfItsOwn) {
  TeleopSession s(command::burger());
  EXPECT_FALSE(s.renewable(0.0)) << "nothing sent yet: nothing to renew";
  s.set_target(v(0.5, 1.0), 0.0);
  ASSERT_TRUE(s.frame_due(0.0, true));
  s.frame_ended(0.2, true, v(0.5, 1.0), 150);
  EXPECT_TRUE(s.renewable(0.2));
  // Joint renewals every 0.4 s: none of its own frames, past half the lease and well after.
  double t = 0.0;
  for (int i = 1; i <= 11; ++i) {
    t = 0.4 * i;
    s.renewed(t);
    s.set_target(v(0.5, 1.0), t);  // the client repeats its target
    EXPECT_FALSE(s.frame_due(t + 0.1, true)) << "at " << t + 0.1 << " s";
  }
  // ... until a frame of its own checks the link (kCheckEvery_s after its last).
  s.set_target(v(0.5, 1.0), 5.0);
  EXPECT_TRUE(s.frame_due(5.0, true)) << "no answer for 5 s: whether the robot still holds it is unknown";
  s.frame_ended(5.2, true, v(0.5, 1.0), 150);
  // Renewals stop coming (its robot left out of them): its own renewal once one is late.
  s.set_target(v(0.5, 1.0), 5.5);
  EXPECT_FALSE(s.frame_due(5.5, true)) << "half the lease: a joint renewal may still come";
  s.set_target(v(0.5, 1.0), 5.75);
  EXPECT_TRUE(s.frame_due(5.75, true)) << "three quarters of the lease without a renewal";
  s.frame_ended(5.9, true, v(0.5, 1.0), 150);
  // A key press goes out at once, renewed or not.
  s.set_target(v(0.6, 1.0), 6.0);
  EXPECT_TRUE(s.frame_due(6.0, true));
}

TEST(TeleopSession, OnlyALiveStreamThatMovesItsRobotIsRenewable) {
  TeleopSession at_rest(command::burger());
  at_rest.set_target(v(0.0), 0.0);
  ASSERT_TRUE(at_rest.frame_due(0.0, true));
  EXPECT_FALSE(at_rest.renewable(0.1)) << "a robot at rest needs no lease";
  TeleopSession silent(command::burger());
  silent.set_target(v(0.3), 0.0);
  ASSERT_TRUE(silent.frame_due(0.0, true));
  EXPECT_TRUE(silent.renewable(0.9));
  EXPECT_FALSE(silent.renewable(1.1)) << "a client silent for a second has gone";
  silent.set_target(v(0.3), 1.2);
  silent.halt("a Stop overtook it");
  EXPECT_FALSE(silent.renewable(1.2));
  TeleopSession ended(command::burger());
  ended.set_target(v(0.3), 0.0);
  ASSERT_TRUE(ended.frame_due(0.0, true));
  ended.end_stream();
  EXPECT_FALSE(ended.renewable(0.1));
}

// The stream looks again only when the session says its rules change: just before that time
// nothing is due, at it something is.
TEST(TeleopSession, ItNamesTheNextTimeItsRulesChange) {
  TeleopSession s(command::burger());
  EXPECT_FALSE(s.next_change_s(0.0, false)) << "no target: only an input changes anything";
  s.set_target(v(0.5, 1.0), 0.0);
  ASSERT_TRUE(s.frame_due(0.0));
  const auto in_flight = s.next_change_s(0.1, false);
  ASSERT_TRUE(in_flight);
  EXPECT_NEAR(*in_flight, server::kClientSilence_s + 0.001, 1e-9)
      << "a frame in flight: its end is an input, and only the client's silence is timed";
  s.frame_ended(0.2, true, v(0.5, 1.0), 120);
  s.set_target(v(0.5, 1.0), 0.3);  // the client repeats its target
  const auto renewal = s.next_change_s(0.3, false);
  ASSERT_TRUE(renewal);
  EXPECT_NEAR(*renewal, 0.5, 1e-9) << "half the lease after the frame was sent";
  EXPECT_FALSE(s.frame_due(*renewal - 0.001));
  EXPECT_TRUE(s.frame_due(*renewal));
  s.halt("a Stop");
  EXPECT_FALSE(s.next_change_s(0.8, false)) << "halted: nothing changes any more";

  // Renewed jointly, a 2 s lease is renewed by the stream only after 1.5 s: the client's
  // silence comes first, and then the lease is renewed no more.
  TeleopSession joint(command::burger());
  joint.set_target(v(0.5, 2.0), 0.0);
  ASSERT_TRUE(joint.frame_due(0.0, true));
  joint.frame_ended(0.2, true, v(0.5, 2.0), 120);
  const auto silence = joint.next_change_s(0.2, true);
  ASSERT_TRUE(silence);
  EXPECT_NEAR(*silence, server::kClientSilence_s + 0.001, 1e-9);
  EXPECT_TRUE(joint.renewable(*silence - 0.002));
  EXPECT_FALSE(joint.renewable(*silence)) << "the silent client's lease is renewed no more";
}
