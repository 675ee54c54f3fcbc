// Signal layer: synthesis, spectrum analysis and peak detection measured against known tones.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "profile/link_profile.h"
#include "signal/peak_detector.h"
#include "signal/spectrum.h"
#include "signal/synthesizer.h"

using namespace dtmf;
using namespace dtmf::signal;

namespace {
std::vector<float> sine(double hz, double amplitude, int n, int rate) {
  std::vector<float> s(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    s[static_cast<std::size_t>(i)] = static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * hz * i / rate));
  return s;
}
}  // namespace

TEST(Spectrum, ASineOnABinReadsItsAmplitude) {
  SpectrumAnalyzer analyzer(4096, 48000);
  const double hz = 100 * analyzer.bin_hz();
  const auto mags = analyzer.analyze(sine(hz, 0.25, 4096, 48000));
  EXPECT_NEAR(mags[100], 0.25, 0.25 * 0.01);
  EXPECT_LT(mags[110], 0.25 * 1e-3);  // far sidelobes of a Hann window are tiny
}

TEST(Spectrum, RejectsWrongWindowSizesAndBadFftSizes) {
  SpectrumAnalyzer analyzer(1024, 48000);
  std::vector<float> short_window(1000);
  EXPECT_THROW(analyzer.analyze(short_window), std::invalid_argument);
  EXPECT_THROW(SpectrumAnalyzer(1000, 48000), std::invalid_argument);
}

TEST(PeakDetector, FindsOffBinTonesWithinOneHertzAndTheirLevel) {
  const LinkProfile& p = seed_profile();
  SpectrumAnalyzer analyzer(p.words().analysis.fft_size, p.sample_rate_hz);
  PeakDetector detector(p.words().robot_detector, analyzer.bin_hz(), 2049);
  std::vector<float> x(4096, 0.0f);
  const std::vector<double> tones = {5123.4, 8877.7, 12001.0, 15555.5};
  add_chord(x, tones, 0.2, 0, p.sample_rate_hz);
  const auto peaks = detector.detect(analyzer.analyze(x));
  ASSERT_GE(peaks.size(), 4u);
  for (double tone : tones) {
    bool found = false;
    for (std::size_t i = 0; i < 4; ++i) {
      if (std::abs(peaks[i].frequency_hz - tone) < 1.0) {
        found = true;
        EXPECT_NEAR(dbfs(peaks[i].amplitude), dbfs(0.2), 0.5);
      }
    }
    EXPECT_TRUE(found) << tone;
  }
}

TEST(PeakDetector, BandPassGateAndCountLimitWhatIsKept) {
  const LinkProfile& p = seed_profile();
  SpectrumAnalyzer analyzer(p.words().analysis.fft_size, p.sample_rate_hz);
  PeakDetector robot(p.words().robot_detector, analyzer.bin_hz(), 2049);
  PeakDetector sender(p.words().sender_detector, analyzer.bin_hz(), 2049);
  std::vector<float> x(4096, 0.0f);
  // 2500 Hz is below the robot's band-pass and inside the sender's; 9000 Hz the reverse.
  add_chord(x, std::vector<double>{2500, 9000}, 0.1, 0, p.sample_rate_hz);
  const std::vector<double> quiet = {6000};  // -80 dBFS: under both gates
  add_chord(x, quiet, 1e-4, 0, p.sample_rate_hz);
  const auto robot_peaks = robot.detect(analyzer.analyze(x));
  ASSERT_FALSE(robot_peaks.empty());
  EXPECT_NEAR(robot_peaks[0].frequency_hz, 9000, 1);
  for (const Peak& peak : robot_peaks) EXPECT_GT(peak.frequency_hz, 4000);
  for (const Peak& peak : robot_peaks) EXPECT_GT(dbfs(peak.amplitude), -60.0);
  const auto sender_peaks = sender.detect(analyzer.analyze(x));
  ASSERT_FALSE(sender_peaks.empty());
  EXPECT_NEAR(sender_peaks[0].frequency_hz, 2500, 1);
  EXPECT_LE(sender_peaks.size(), 5u);
}

TEST(Synthesizer, ChordHasTheProfileLengthSmoothEdgesAndBoundedLevel) {
  const LinkProfile& p = seed_profile();
  const auto chord = synthesize_frame(p, 0xB2DD);
  EXPECT_EQ(chord.size(), static_cast<std::size_t>(p.samples_for_ms(p.timing.chord_ms)));
  EXPECT_LT(std::abs(chord.front()), 1e-3);
  EXPECT_LT(std::abs(chord.back()), 1e-2);
  float peak = 0;
  for (float s : chord) peak = std::max(peak, std::abs(s));
  EXPECT_LE(peak, 4 * p.words().tones.tone_amplitude + 1e-5);
  EXPECT_GT(peak, 2 * p.words().tones.tone_amplitude);
  const auto reply = synthesize_reply(p, Reply::Ack);
  EXPECT_EQ(reply.size(), static_cast<std::size_t>(p.samples_for_ms(p.timing.ack_ms)));
}

TEST(Synthesizer, EdgesKeepSplatterOutOfTheOtherPlanTones) {
  // A chord cut out of silence: the plan tones it does not use must stay 40 dB under it.
  const LinkProfile& p = seed_profile();
  std::vector<float> x(4096, 0.0f);
  std::vector<float> chord = synthesize_chord(p, std::vector<double>{6000}, 40);
  std::copy(chord.begin(), chord.end(), x.begin() + 1500);
  SpectrumAnalyzer analyzer(4096, p.sample_rate_hz);
  const auto mags = analyzer.analyze(x);
  const auto bin = [&](double hz) { return mags[static_cast<std::size_t>(std::lround(hz / analyzer.bin_hz()))]; };
  const double tone = bin(6000);
  for (double other : {4500.0, 7500.0, 10500.0, 13500.0}) EXPECT_LT(dbfs(bin(other)) - dbfs(tone), -40) << other;
}
