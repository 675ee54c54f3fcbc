// Signal layer: the per-bin background learns a whine within seconds and never a chord's tone.
#include <gtest/gtest.h>

#include <vector>

#include "signal/steady_background.h"

using dtmf::signal::SteadyBackground;

namespace {
constexpr double kWindowsPerS = 20;  // the seed profile's analysis rate
constexpr float kFloor = 0.001f;     // -60 dBFS
}  // namespace

TEST(SteadyBackground, AWhineBecomesBackgroundWhileAChordsToneStaysAboveIt) {
  SteadyBackground background(3, 10.0, kWindowsPerS, kFloor);
  // bin 0: a whine of 0.1 from the start; bin 1: quiet; bin 2: a chord tone of 0.1 at 8 s.
  std::vector<float> m{0.1f, 0.0005f, 0.0005f};
  int learnt_after_windows = -1;
  for (int w = 0; w < 8 * kWindowsPerS; ++w) {
    const auto excess = background.remove(m);
    if (learnt_after_windows < 0 && excess[0] < 0.01f) learnt_after_windows = w;
  }
  // 40 dB from the floor at 10 dB/s: 4 s, i.e. 80 windows.
  EXPECT_NEAR(learnt_after_windows, 80, 2);
  m[2] = 0.1f;
  float weakest_excess = 1.0f;
  for (int w = 0; w < 0.8 * kWindowsPerS; ++w) weakest_excess = std::min(weakest_excess, background.remove(m)[2]);
  // After 0.8 s the background under the tone has risen 8 dB from the floor: -52 dBFS.
  EXPECT_GT(weakest_excess, 0.099f);
  EXPECT_LT(background.remove(m)[0], 0.01f) << "the whine stays learnt";
  EXPECT_EQ(background.remove(m)[1], 0.0f) << "a quiet bin has no excess";
}

TEST(SteadyBackground, AFallIsFollowedAtOnceSoAToneAfterSilenceIsWhole) {
  SteadyBackground background(1, 10.0, kWindowsPerS, kFloor);
  std::vector<float> m{0.1f};
  for (int w = 0; w < 200; ++w) background.remove(m);  // learnt
  m[0] = 0.0001f;
  background.remove(m);  // one window of silence
  m[0] = 0.1f;
  EXPECT_NEAR(background.remove(m)[0], 0.1f, 0.001f);
}

TEST(SteadyBackground, ZeroRiseLeavesTheSpectrumAsItIs) {
  SteadyBackground off(2, 0.0, kWindowsPerS, kFloor);
  const std::vector<float> m{0.5f, 0.25f};
  for (int w = 0; w < 100; ++w) EXPECT_EQ(off.remove(m)[0], 0.5f);
  EXPECT_THROW(SteadyBackground(1, -1.0, kWindowsPerS, kFloor), std::invalid_argument);
}
