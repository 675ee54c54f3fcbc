// The spectrum's columns for watchers (signal/spectrum_columns.h): where a tone shows, how
// loud, and how many columns a second of audio gives.
#include "signal/spectrum_columns.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using dtmf::signal::SpectrumColumns;

namespace {
std::vector<float> tone(double hz, double dbfs, double seconds, int rate_hz = 48000) {
  std::vector<float> s(static_cast<std::size_t>(seconds * rate_hz));
  const double amplitude = std::pow(10.0, dbfs / 20);
  for (std::size_t i = 0; i < s.size(); ++i)
    s[i] = static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * hz * static_cast<double>(i) / rate_hz));
  return s;
}
}  // namespace

TEST(SpectrumColumns, ATonesLevelShowsInItsBinAndNowhereNear) {
  SpectrumColumns columns(48000, 1000, 20000, 190, 20);  // 100 Hz bins
  const auto all = columns.feed(tone(4550, -20, 0.5));
  ASSERT_EQ(all.size(), 10u);  // 0.5 s at 20 a second
  const auto& last = all.back();
  ASSERT_EQ(last.level_dbfs.size(), 190u);
  EXPECT_DOUBLE_EQ(last.end_audio_ms, 500);
  const auto loudest = std::max_element(last.level_dbfs.begin(), last.level_dbfs.end());
  EXPECT_EQ(loudest - last.level_dbfs.begin(), 35);  // 4500..4600 Hz
  EXPECT_NEAR(*loudest, -20, 1.5);                   // Hann scalloping at most 1.4 dB
  EXPECT_LT(last.level_dbfs[60], -80);               // 7 kHz: only the window's sidelobes
}

TEST(SpectrumColumns, SilenceReadsAtTheFloor) {
  SpectrumColumns columns(48000, 1000, 20000, 64, 50);
  const auto all = columns.feed(std::vector<float>(48000, 0.0f));
  ASSERT_EQ(all.size(), 50u);
  for (float level : all.back().level_dbfs) EXPECT_EQ(level, SpectrumColumns::kFloorDbfs);
}

TEST(SpectrumColumns, ColumnsComeDueAcrossBlocks) {
  SpectrumColumns columns(48000, 1000, 20000, 64, 10);  // one column every 4800 samples
  std::size_t got = 0;
  for (int block = 0; block < 100; ++block) got += columns.feed(std::vector<float>(480, 0.0f)).size();
  EXPECT_EQ(got, 10u);
}

TEST(SpectrumColumns, RefusesABandPastNyquist) {
  EXPECT_THROW(SpectrumColumns(16000, 1000, 20000, 64, 10), std::invalid_argument);
}
