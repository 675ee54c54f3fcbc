// dtmf-room's real-time keeper (tools/room/lag_keeper.h): a chain that keeps pace drops
// nothing; after a stall, the queued audio beyond the allowance is dropped, once.
#include <gtest/gtest.h>

#include "lag_keeper.h"

using dtmf::room::LagKeeper;

namespace {
constexpr int kRate = 48000;
constexpr std::size_t kBlock = 480;  // 10 ms
}  // namespace

TEST(LagKeeper, AChainThatKeepsPaceLosesNothingEvenWithJitter) {
  LagKeeper keeper(kRate, 50);
  double now = 1000;
  for (int i = 0; i < 1000; ++i) {
    now += 10 + ((i % 7) - 3) * 4.0;  // reads up to 12 ms early or late
    EXPECT_EQ(keeper.to_drop(now, kBlock), 0u) << i;
  }
  EXPECT_EQ(keeper.dropped(), 0u);
}

// A filter between a recording that queues and a playback that paces: a block it writes
// waits for the playback (10 ms), a block it drops whole does not, so the next queued one is
// read at once.
struct Chain {
  LagKeeper keeper{kRate, 50};
  double now_ms = 0;
  std::size_t step() {
    const std::size_t drop = keeper.to_drop(now_ms, kBlock);
    now_ms += drop == kBlock ? 0.05 : 10;
    return drop;
  }
};

TEST(LagKeeper, AfterAStallTheQueuedAudioBeyondTheAllowanceIsDroppedOnce) {
  Chain chain;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(chain.step(), 0u);
  chain.now_ms += 300;  // a stall
  std::size_t dropped = 0;
  for (int i = 0; i < 100; ++i) dropped += chain.step();
  // About the stall (300 ms = 14400 samples, less the few ms it catches up to), not more.
  EXPECT_NEAR(static_cast<double>(dropped), 300.0 * kRate / 1000, 2 * kBlock);
  EXPECT_EQ(chain.keeper.dropped(), dropped);
  // Caught up: the next blocks pass whole.
  for (int i = 0; i < 100; ++i) EXPECT_EQ(chain.step(), 0u) << i;
}

TEST(LagKeeper, AStallWithinTheAllowanceIsKept) {
  LagKeeper keeper(kRate, 50);
  double now = 0;
  for (int i = 0; i < 50; ++i) keeper.to_drop(now += 10, kBlock);
  now += 40;
  for (int i = 0; i < 50; ++i) EXPECT_EQ(keeper.to_drop(now += 10, kBlock), 0u);
}
