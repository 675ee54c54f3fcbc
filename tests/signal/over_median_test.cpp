// Signal layer: the counted median test against the sorted median it replaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "signal/over_median.h"

using dtmf::signal::over_median;

namespace {
bool over_sorted_median(std::vector<float> powers, float level, float ratio) {
  std::nth_element(powers.begin(), powers.begin() + static_cast<std::ptrdiff_t>(powers.size() / 2), powers.end());
  return level > ratio * powers[powers.size() / 2];
}
}  // namespace

TEST(OverMedian, AgreesWithTheSortedMedianWhateverTheSizeTiesOrLevel) {
  std::mt19937 rng(11);
  std::exponential_distribution<float> power(1.0f);
  std::uniform_int_distribution<int> few(0, 3);
  int over = 0, under = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(trial % 40);
    std::vector<float> powers(n);
    // Every fourth trial draws from four values only: ties at the median.
    for (float& p : powers) p = trial % 4 == 0 ? static_cast<float>(few(rng)) : power(rng);
    const float ratio = 4.0f;
    // Levels around ratio x median, the median itself among them.
    std::vector<float> sorted = powers;
    std::sort(sorted.begin(), sorted.end());
    for (const float level : {0.0f, ratio * sorted[n / 2], std::nextafter(ratio * sorted[n / 2], 1e30f),
                              ratio * sorted[n / 2] * 0.9f, ratio * sorted[n / 2] * 1.1f, ratio * sorted.back() + 1}) {
      const bool expected = over_sorted_median(powers, level, ratio);
      ASSERT_EQ(over_median(powers, level, ratio), expected) << "n " << n << " level " << level;
      (expected ? over : under)++;
    }
  }
  // Both answers came up often (the comparison could tell a wrong count).
  EXPECT_GT(over, 20000);
  EXPECT_GT(under, 20000);
}

TEST(OverMedian, ATonesPowerOverItsBandsFloor) {
  // A band of 32 bins at power 1 with one tone at 10: 10 > 4 x 1.
  std::vector<float> band(32, 1.0f);
  band[7] = 10.0f;
  EXPECT_TRUE(over_median(band, 10.0f, 4.0f));
  EXPECT_FALSE(over_median(band, 3.9f, 4.0f));
  // Half the bins loud (a chord smeared over the band): the floor is loud too.
  std::fill(band.begin(), band.begin() + 17, 5.0f);
  EXPECT_FALSE(over_median(band, 10.0f, 4.0f));
}
