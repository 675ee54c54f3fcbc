// The carrier sense (reliability/carrier_sense.h) in the simulator's noise (sim/noise.h):
// steady noise is no sound, in a quiet room and in a lone sender's pauses between runs of
// its own frames, and a faint chord over that noise is heard within a slot. Before a sound
// had to last, 5 ms blocks of pink noise at -50 dBFS passed the busy mark 16 times in 5
// minutes, and a lone sender took its room for shared.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "reliability/air_access.h"
#include "reliability/carrier_sense.h"
#include "sim/noise.h"

using namespace dtmf;
using reliability::CarrierSense;

namespace {

constexpr int kRateHz = 48000;
constexpr int kBlockSamples = 240;  // 5 ms, the sender's answer hop
constexpr double kBlockMs = 1000.0 * kBlockSamples / kRateHz;
constexpr double kNoiseDbfs = -50;

struct NoisyAir {
  explicit NoisyAir(const char* kind, std::uint64_t seed) : noise(sim::parse_noise(kind, kNoiseDbfs), kRateHz, seed) {}
  // `ms` of noise, plus a tone of `tone_dbfs` RMS (none: below -200) into every block.
  void hear(double ms, double tone_dbfs = -300) {
    std::vector<float> block(kBlockSamples);
    const double amplitude = std::sqrt(2.0) * std::pow(10.0, (tone_dbfs - 3) / 20);  // 0 dBFS: a full-scale sine
    for (double end = t + ms; t < end - 1e-9;) {
      std::fill(block.begin(), block.end(), 0.0f);
      noise.add_to(block);
      for (std::size_t i = 0; i < block.size(); ++i, ++n)
        block[i] += static_cast<float>(amplitude * std::sin(2 * M_PI * 1500.0 * static_cast<double>(n) / kRateHz));
      t += kBlockMs;
      sense.hear(reliability::block_level_dbfs(block), t);
      if (sense.busy_now() && !first_busy_ms) first_busy_ms = t;
    }
  }
  // Our own sound: blocks at `level_dbfs`, for `ms`.
  void own(double ms, double level_dbfs) {
    for (double end = t + ms; t < end - 1e-9;) {
      t += kBlockMs;
      sense.hear(level_dbfs, t);
    }
  }
  sim::NoiseSource noise;
  CarrierSense sense;
  double t = 0;
  long long n = 0;
  std::optional<double> first_busy_ms;  // the end of the first block heard busy
};

}  // namespace

TEST(CarrierSenseInNoise, FiveMinutesOfPinkOrWhiteNoiseAreNoSound) {
  for (const char* kind : {"pink", "white"}) {
    NoisyAir air(kind, 1);
    air.hear(300'000);
    EXPECT_EQ(air.sense.busy_blocks(), 0u) << kind;
    EXPECT_NEAR(air.sense.floor_dbfs(), kNoiseDbfs, 3) << kind;
  }
}

// A lone sender: 20 s of exchanges back to back (a 150 ms frame, 40 ms of its tail gone into
// the noise, its robot's 60 ms answer, 30 ms to the next), then its listening pause.
TEST(CarrierSenseInNoise, ALoneSendersRunsAndPausesHearNobody) {
  int heard = 0;
  for (int trial = 0; trial < 20; ++trial) {
    NoisyAir air("pink", 100 + trial);
    air.hear(2000);
    while (air.t < 22'000) {
      air.sense.own_begin(air.t);
      air.own(150, -20);
      air.sense.frame_ended(air.t);
      air.hear(40);
      const double answer_from = air.t;
      air.hear(60, -30);
      air.sense.own_end(air.t, reliability::AirSpan{answer_from, air.t});
      air.hear(30);
    }
    air.hear(2000);
    heard += air.sense.busy_blocks() > 0 ? 1 : 0;
  }
  EXPECT_EQ(heard, 0) << "trials in which a lone sender heard another (before: 4 in 20)";
}

TEST(CarrierSenseInNoise, AChordTwelveDecibelsOverPinkNoiseIsHeardWithinASlot) {
  NoisyAir air("pink", 7);
  air.hear(3000);
  const double mark_dbfs = air.sense.floor_dbfs() + reliability::kBusyOverFloorDb;
  const double from = air.t;
  air.hear(60, mark_dbfs + 2);
  ASSERT_TRUE(air.first_busy_ms);
  EXPECT_LE(*air.first_busy_ms - from, reliability::kSlotMs);
  EXPECT_DOUBLE_EQ(*air.sense.last_busy_ms(), air.t) << "heard to its end";
}
