// RefusalBurst: one warning per burst of authentication refusals, none for a few.
#include "refusal_burst.h"

#include <gtest/gtest.h>

using dtmf::agent::kBurstPerMinute;
using dtmf::agent::RefusalBurst;

TEST(RefusalBurst, NineInAMinuteAreNoBurstTheTenthIsOnce) {
  RefusalBurst burst;
  for (int i = 0; i < kBurstPerMinute - 1; ++i) EXPECT_FALSE(burst.refused(i * 5000.0)) << i;
  const auto begun = burst.refused(50'000);
  ASSERT_TRUE(begun);
  EXPECT_EQ(*begun, kBurstPerMinute);
  // A forger at full rate: still the one warning.
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(burst.refused(50'000 + i * 153.75)) << i;
  EXPECT_GT(burst.in_last_minute(), 300);
}

TEST(RefusalBurst, TheSameCountSpreadOverMoreThanAMinuteIsNoBurst) {
  RefusalBurst burst;
  // One every 6.7 s: nine within any 60 s, never ten.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(burst.refused(i * 6700.0)) << i;
  EXPECT_EQ(burst.in_last_minute(), kBurstPerMinute - 1);
}

TEST(RefusalBurst, ABurstAfterTheRateFellIsSaidAgain) {
  RefusalBurst burst;
  for (int i = 0; i < kBurstPerMinute; ++i) burst.refused(i * 100.0);
  EXPECT_FALSE(burst.refused(2000));
  // Quiet for two minutes, then another burst.
  int warnings = 0;
  for (int i = 0; i < kBurstPerMinute; ++i) warnings += burst.refused(200'000 + i * 100.0) ? 1 : 0;
  EXPECT_EQ(warnings, 1);
}
