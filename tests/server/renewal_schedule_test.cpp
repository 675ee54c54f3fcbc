// When the sender renews its robots' leases jointly (server/core/renewal_schedule.h).
#include "renewal_schedule.h"

#include <gtest/gtest.h>

using dtmf::server::RenewalSchedule;
using Robots = std::vector<RenewalSchedule::Robot>;

TEST(RenewalSchedule, NothingIsDueUntilARobotsPeriodHasPassedThenEveryKeptRobotIsRenewed) {
  RenewalSchedule s;
  EXPECT_FALSE(s.next_due_ms());
  s.keep(0, 450, 1000, 1000);
  s.keep(2, 450, 1000, 1200);
  EXPECT_EQ(s.next_due_ms(), 1450);
  EXPECT_TRUE(s.due(1449, 3).empty());
  EXPECT_EQ(s.due(1450, 3), (Robots{0, 2})) << "robot 2 rides along: the frame costs the same";
  s.frame_started(0, 1460);
  s.frame_started(2, 1460);
  EXPECT_EQ(s.next_due_ms(), 1910);
}

TEST(RenewalSchedule, AFrameOfItsOwnPutsARobotsRenewalOff) {
  RenewalSchedule s;
  s.keep(1, 450, 1000, 0);
  s.frame_started(1, 300);  // a key press: a velocity frame of its own
  EXPECT_TRUE(s.due(450, 3).empty());
  EXPECT_EQ(s.due(750, 3), Robots{1});
  s.frame_started(1, 100);  // an older start changes nothing
  EXPECT_EQ(s.next_due_ms(), 750);
}

TEST(RenewalSchedule, AFrameHoldsAtMostThreeTheLongestUnrenewedFirst) {
  RenewalSchedule s;
  for (RenewalSchedule::Robot r = 0; r < 4; ++r) s.keep(r, 450, 1000, 100.0 * static_cast<double>(4 - r));
  EXPECT_EQ(s.due(900, 3), (Robots{3, 2, 1}));
  for (const auto r : Robots{3, 2, 1}) s.frame_started(r, 900);
  EXPECT_EQ(s.due(900, 3), (Robots{0, 1, 2})) << "the one left out is due still, and goes first";
}

TEST(RenewalSchedule, ARobotDroppedIsNeverDue) {
  RenewalSchedule s;
  s.keep(0, 450, 1000, 0);
  s.keep(0, 900, 2000, 0);  // kept again: its new period
  EXPECT_EQ(s.next_due_ms(), 900);
  s.drop(0);
  EXPECT_TRUE(s.due(10000, 3).empty());
  EXPECT_FALSE(s.next_due_ms());
  s.frame_started(0, 5);  // a frame of a robot no longer kept keeps it dropped
  EXPECT_FALSE(s.kept(0));
}

// A wait for an answer ends before the first kept robot's lease would run out unrenewed (the
// fleet teleop bench: a lost ACK after a key press held the air for 500 ms, and a lease ran out).
TEST(RenewalSchedule, TheFirstLeaseToRunOutIsTheOldestRenewalsLease) {
  RenewalSchedule s;
  EXPECT_FALSE(s.first_lease_end_ms());
  s.keep(0, 400, 1000, 0);
  s.keep(1, 400, 2000, 0);
  EXPECT_EQ(s.first_lease_end_ms(), 1000);
  s.frame_started(0, 300);  // robot 0 had a velocity frame of its own
  EXPECT_EQ(s.first_lease_end_ms(), 1300);
  s.frame_started(1, 300);
  EXPECT_EQ(s.first_lease_end_ms(), 1300) << "robot 1's lease is longer";
  s.drop(0);
  EXPECT_EQ(s.first_lease_end_ms(), 2300);
  s.drop(1);
  EXPECT_FALSE(s.first_lease_end_ms());
}
