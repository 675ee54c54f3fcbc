// Signal layer: the windows the fast listener keeps for a second look — they wait out the
// delay, leave when due, and a frame taken in or after a window drops it.
#include <gtest/gtest.h>

#include <vector>

#include "signal/reread_queue.h"

using dtmf::signal::HopCandidate;
using dtmf::signal::RereadQueue;

namespace {
std::vector<long long> ends(std::span<const dtmf::signal::PendingWindow> due) {
  std::vector<long long> out;
  for (const auto& p : due) out.push_back(p.end_sample);
  return out;
}
}  // namespace

TEST(RereadQueue, AWindowIsDueOnceItsDelayHasPassedAndOnlyOnce) {
  RereadQueue q(100);
  HopCandidate c;
  c.offset_ppm = 250;
  q.keep(2, 1000, std::span(&c, 1));
  q.keep(3, 1050, {});
  EXPECT_TRUE(ends(q.take_due(1099, -1)).empty());
  const auto due = q.take_due(1100, -1);
  ASSERT_EQ(ends(due), std::vector<long long>{1000});
  EXPECT_EQ(due[0].chords, 2);
  ASSERT_EQ(due[0].hypotheses, 1u);
  EXPECT_EQ(due[0].grid[0].offset_ppm, 250);
  EXPECT_EQ(ends(q.take_due(1200, -1)), std::vector<long long>{1050});
  EXPECT_TRUE(q.empty());
}

TEST(RereadQueue, AFrameTakenInOrAfterAWindowDropsIt) {
  RereadQueue q(100);
  q.keep(2, 1000, {});
  q.keep(2, 1010, {});
  q.keep(2, 1020, {});
  // A frame taken from the window that ended at 1010: it, and the one before, are its own.
  EXPECT_EQ(ends(q.take_due(1200, 1010)), std::vector<long long>{1020});
  q.keep(2, 2000, {});
  q.clear();
  EXPECT_TRUE(q.empty());
}

TEST(RereadQueue, KeepsNothingWithoutADelayOrPastItsCapacity) {
  RereadQueue off(0);
  off.keep(2, 1000, {});
  EXPECT_TRUE(off.empty());
  RereadQueue q(100);
  for (long long i = 0; i < 10; ++i) q.keep(2, 1000 + i, {});
  EXPECT_EQ(q.take_due(5000, -1).size(), RereadQueue::kCapacity);
}
