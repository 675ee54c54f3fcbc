// Physical layer: the simulated room measured against its own physics.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physical/wav_file.h"
#include "signal/peak_detector.h"
#include "signal/spectrum.h"
#include "signal/synthesizer.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;
using namespace dtmf::sim;
using namespace dtmf::physical;

namespace {

constexpr int kRate = 48000;

std::vector<float> run(AcousticChannel& channel, const std::vector<float>& in) {
  std::vector<float> out;
  channel.process(in, out);
  return out;
}

std::vector<float> tone(double hz, double seconds, double amplitude = 0.5) {
  std::vector<float> x(static_cast<std::size_t>(seconds * kRate));
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * hz * i / kRate));
  return x;
}

double rms(std::span<const float> x) {
  double p = 0;
  for (float s : x) p += static_cast<double>(s) * s;
  return std::sqrt(p / static_cast<double>(x.size()));
}

}  // namespace

TEST(AcousticChannel, SoundArrivesAfterDistanceOverTheSpeedOfSound) {
  for (double d : {1.0, 3.43, 10.0}) {
    AcousticChannel channel(kRate, {});
    channel.add_transmitter(d);
    std::vector<float> click(kRate, 0.0f);
    click[1000] = 1.0f;
    const auto out = run(channel, click);
    const double expected = 1000 + d / kSpeedOfSoundMps * kRate;
    // The FIR spreads the click over a few samples around its centre.
    std::size_t loudest = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
      if (std::abs(out[i]) > std::abs(out[loudest])) loudest = i;
    EXPECT_NEAR(static_cast<double>(loudest), expected, 1.0) << d;
  }
}

TEST(AcousticChannel, LevelFallsWithSpreadingAndHighTonesLoseMoreToTheAir) {
  for (double d : {1.0, 4.0, 10.0, 20.0}) {
    for (double hz : {1000.0, 8000.0, 16000.0}) {
      AcousticChannel channel(kRate, {});
      channel.add_transmitter(d);
      const auto out = run(channel, tone(hz, 0.5));
      const double measured_db = 20 * std::log10(rms(std::span(out).subspan(4000)) / (0.5 / std::sqrt(2)));
      EXPECT_NEAR(-measured_db, channel_loss_db(hz, d), 0.3) << d << " m, " << hz << " Hz";
    }
  }
  // The fit to ISO 9613-1: about 0.12 dB/m at 8 kHz and 0.46 dB/m at 16 kHz.
  EXPECT_NEAR(channel_loss_db(8000, 1), 0.115, 0.01);
  EXPECT_NEAR(channel_loss_db(16000, 10) - 20, 4.6, 0.1);
}

TEST(AcousticChannel, TransmittersAddUp) {
  AcousticChannel both(kRate, {});
  both.add_transmitter(2.0);
  both.add_transmitter(2.0);
  const auto x = tone(5000, 0.2);
  const std::span<const float> blocks[2] = {x, x};
  std::vector<float> out;
  both.process(blocks, out);
  AcousticChannel one(kRate, {});
  one.add_transmitter(2.0);
  const auto single = run(one, x);
  ASSERT_EQ(out.size(), single.size());
  for (std::size_t i = 0; i < out.size(); i += 101) EXPECT_NEAR(out[i], 2 * single[i], 1e-5);
}

TEST(AcousticChannel, NoiseHasTheRequestedLevelAndIsDeterministicPerSeed) {
  for (const char* kind : {"white", "pink"}) {
    ChannelConfig config;
    config.noise = parse_noise(kind, -30);
    config.seed = 7;
    AcousticChannel a(kRate, config), b(kRate, config);
    a.add_transmitter(1);
    b.add_transmitter(1);
    const std::vector<float> silence(kRate * 2, 0.0f);
    const auto na = run(a, silence), nb = run(b, silence);
    EXPECT_NEAR(20 * std::log10(rms(na)), -30, 0.3) << kind;
    EXPECT_EQ(na, nb) << kind;
    config.seed = 8;
    AcousticChannel c(kRate, config);
    c.add_transmitter(1);
    EXPECT_NE(run(c, silence), na) << kind;
  }
}

TEST(AcousticChannel, PinkNoiseFallsThreeDecibelsPerOctave) {
  ChannelConfig config;
  config.noise = parse_noise("pink", -20);
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1);
  const auto noise = run(channel, std::vector<float>(kRate * 4, 0.0f));
  signal::SpectrumAnalyzer analyzer(4096, kRate);
  std::vector<double> power(2049, 0.0);
  for (std::size_t start = 0; start + 4096 <= noise.size(); start += 2048) {
    const auto mags = analyzer.analyze(std::span(noise).subspan(start, 4096));
    for (std::size_t k = 0; k < power.size(); ++k) power[k] += mags[k] * mags[k];
  }
  auto band_db = [&](double lo) {
    double sum = 0;
    int n = 0;
    for (auto k = static_cast<std::size_t>(lo / analyzer.bin_hz());
         k < static_cast<std::size_t>(lo * 1.2 / analyzer.bin_hz()); ++k, ++n)
      sum += power[k];
    return 10 * std::log10(sum / n);
  };
  // Per-bin power of pink noise halves per octave: -3 dB from 2 to 4 kHz and 4 to 8 kHz.
  EXPECT_NEAR(band_db(4000) - band_db(2000), -3.0, 0.7);
  EXPECT_NEAR(band_db(8000) - band_db(4000), -3.0, 0.7);
}

TEST(AcousticChannel, ClockOffsetStretchesTheRecordingAndShiftsTones) {
  ChannelConfig config;
  config.clock_offset_ppm = 1000;  // exaggerated, to be measurable
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1);
  const auto in = tone(12000, 1.0);
  std::vector<float> out;
  for (std::size_t i = 0; i < in.size(); i += 480) channel.process(std::span(in).subspan(i, 480), out);
  // The resampler's sinc looks ahead about 47 samples, which it holds back until more come.
  EXPECT_NEAR(static_cast<double>(out.size()), in.size() * 1.001 - 47, 5.0);
  // A faster microphone clock hears every tone lower by the same fraction.
  signal::SpectrumAnalyzer analyzer(4096, kRate);
  signal::PeakDetector peaks(DetectorParams{4000, 17000, 1, -60, 25}, analyzer.bin_hz(), 2049);
  const auto found = peaks.detect(analyzer.analyze(std::span(out).subspan(10000, 4096)));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].frequency_hz, 12000 / 1.001, 1.0);
}

TEST(AcousticChannel, ReverberationLeavesATailThatDecaysWithRt60) {
  ChannelConfig config;
  config.reverb.rt60_s = 0.5;
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1);
  std::vector<float> burst = tone(6000, 0.2);
  burst.resize(kRate * 2, 0.0f);
  const auto out = run(channel, burst);
  const auto at = [&](double s) { return rms(std::span(out).subspan(static_cast<std::size_t>(s * kRate), 2400)); };
  EXPECT_GT(at(0.3), 1e-3);  // still ringing 0.1 s after the burst
  const double decay_db = 20 * std::log10(at(0.7) / at(0.3));
  EXPECT_NEAR(decay_db, -60 * 0.4 / 0.5, 12);  // about 60 dB per RT60
  AcousticChannel dry(kRate, {});
  dry.add_transmitter(1);
  const auto dry_out = run(dry, burst);
  EXPECT_LT(rms(std::span(dry_out).subspan(static_cast<std::size_t>(0.3 * kRate), 2400)), 1e-6);
}

TEST(AcousticChannel, BadDistancesAndBlockCountsAreRefused) {
  AcousticChannel channel(kRate, {});
  EXPECT_THROW(channel.add_transmitter(0), std::invalid_argument);
  EXPECT_THROW(channel.add_transmitter(-3), std::invalid_argument);
  EXPECT_THROW(channel.add_transmitter(std::nan("")), std::invalid_argument);
  channel.add_transmitter(1);
  channel.add_transmitter(2);
  std::vector<float> out;
  EXPECT_THROW(channel.process(std::vector<float>(10), out), std::invalid_argument);
}

TEST(AcousticChannel, ANoiseRecordingIsLoopedAtTheRequestedLevel) {
  const std::string path = ::testing::TempDir() + "/noise-src.wav";
  write_wav_file(path, tone(3000, 0.3, 0.1), kRate);
  ChannelConfig config;
  config.noise = parse_noise(path, -20);
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1);
  const auto out = run(channel, std::vector<float>(kRate, 0.0f));  // 1 s from a 0.3 s loop
  EXPECT_NEAR(20 * std::log10(rms(out)), -20, 0.5);
  ChannelConfig silent;
  silent.noise = parse_noise(path + ".missing", -20);
  EXPECT_THROW(AcousticChannel(kRate, silent), AudioError);
}
