// The partitioned convolver against plain convolution, split any way, and its speed.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "room_test_support.h"
#include "sim/fft_convolver.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

std::vector<float> random_signal(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<float> x(n);
  for (float& s : x) s = g(rng);
  return x;
}

std::vector<float> direct_convolution(std::span<const float> h, std::span<const float> x) {
  std::vector<float> y(x.size(), 0.0f);
  for (std::size_t n = 0; n < x.size(); ++n) {
    double acc = 0;
    for (std::size_t k = 0; k < h.size() && k <= n; ++k) acc += static_cast<double>(h[k]) * x[n - k];
    y[n] = static_cast<float>(acc);
  }
  return y;
}

}  // namespace

TEST(FftConvolver, EqualsDirectConvolutionWithNoLatencyForEveryStageLayout) {
  // Lengths that end inside the head, inside each stage and just past a stage's edge.
  for (std::size_t taps : {1u, 40u, 64u, 65u, 300u, 512u, 513u, 4097u, 9000u}) {
    const auto h = random_signal(taps, 1);
    const auto x = random_signal(12000, 2);
    FftConvolver convolver(h);
    std::vector<float> y(x.size(), 0.0f);
    convolver.process_add(x, y);
    const auto expected = direct_convolution(h, x);
    double error = 0, power = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
      error += (y[i] - expected[i]) * (y[i] - expected[i]);
      power += expected[i] * expected[i];
    }
    EXPECT_LT(10 * std::log10(error / power), -100) << taps << " taps";
    EXPECT_NEAR(y[0], h[0] * x[0], 1e-5) << "no latency, " << taps << " taps";
  }
}

TEST(FftConvolver, AnySplitOfTheStreamGivesTheSameSamples) {
  const auto h = random_signal(20000, 3);
  const auto x = random_signal(30000, 4);
  FftConvolver whole(h);
  std::vector<float> expected(x.size(), 0.0f);
  whole.process_add(x, expected);
  for (std::size_t block : {1u, 7u, 64u, 100u, 4096u, 5000u}) {
    FftConvolver split(h);
    std::vector<float> y(x.size(), 0.0f);
    for (std::size_t i = 0; i < x.size(); i += block) {
      const std::size_t n = std::min(block, x.size() - i);
      split.process_add(std::span(x).subspan(i, n), std::span(y).subspan(i, n));
    }
    EXPECT_EQ(y, expected) << "blocks of " << block;
  }
}

TEST(FftConvolver, StreamsATwoAndAHalfSecondResponseManyTimesFasterThanRealTime) {
  const auto h = random_signal(static_cast<std::size_t>(2.5 * kRate), 5);
  const auto x = random_signal(10 * kRate, 6);
  FftConvolver convolver(h);
  std::vector<float> y(x.size(), 0.0f);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < x.size(); i += 480)
    convolver.process_add(std::span(x).subspan(i, 480), std::span(y).subspan(i, 480));
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double speed = 10.0 / took_s;
  std::printf("[ figures  ] 2.5 s response, 10 ms blocks: %.0f x real time\n", speed);
  EXPECT_GT(speed, 20.0);
}
