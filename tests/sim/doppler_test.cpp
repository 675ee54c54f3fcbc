// Frequency shifts: a microphone clock off by up to +-3000 ppm and a transmitter driving
// towards or away from the microphone shift a tone to exactly the predicted frequency,
// cleanly; a moving transmitter's sound arrives d(t)/c late at level 1/d(t).
#include <gtest/gtest.h>

#include <numeric>

#include "room_test_support.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

// The largest spectral line more than `guard_hz` away from `hz`, relative to the one at
// `hz`, dB (Blackman-Harris-like dynamic range from a long Hann window is enough here).
double worst_spur_db(std::span<const float> x, double hz, double guard_hz) {
  const RealFft fft(1u << 17);
  FftReal buffer(fft.size(), 0.0f);
  const std::size_t n = std::min(x.size(), fft.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.35875 - 0.48829 * std::cos(2 * std::numbers::pi * i / (n - 1)) +
                     0.14128 * std::cos(4 * std::numbers::pi * i / (n - 1)) -
                     0.01168 * std::cos(6 * std::numbers::pi * i / (n - 1));
    buffer[i] = static_cast<float>(x[i] * w);
  }
  FftBins bins(fft.bins());
  fft.forward(buffer.data(), bins.data());
  const double bin_hz = static_cast<double>(kRate) / static_cast<double>(fft.size());
  double main = 0, spur = 0;
  for (std::size_t k = 1; k < bins.size(); ++k) {
    const double f = static_cast<double>(k) * bin_hz;
    (std::abs(f - hz) < guard_hz ? main : spur) =
        std::max(std::abs(f - hz) < guard_hz ? main : spur, static_cast<double>(std::abs(bins[k])));
  }
  return 20 * std::log10(spur / main);
}

}  // namespace

TEST(Doppler, AClockOffsetOfUpTo3000PpmShiftsATenKilohertzToneExactlyAndCleanly) {
  for (double ppm : {-3000.0, -100.0, 3000.0}) {
    ChannelConfig config;
    config.clock_offset_ppm = ppm;
    AcousticChannel channel(kRate, config);
    channel.add_transmitter(1.0);
    const auto in = tone(10000, 2.0);
    const auto out = through(channel, in, 480);
    EXPECT_NEAR(static_cast<double>(out.size()), static_cast<double>(in.size()) * (1 + ppm * 1e-6), 80) << ppm;
    const auto steady = std::span(out).subspan(4800, 86400);
    EXPECT_NEAR(peak_frequency_hz(steady, 9800, 10200), 10000 / (1 + ppm * 1e-6), 1.0) << ppm;
  }
  // The top tone, a third of the rate, stays one clean line at 3000 ppm (an interpolating
  // cubic would leave 144 Hz sidebands about 15 dB down, and a level that wobbles).
  ChannelConfig config;
  config.clock_offset_ppm = 3000;
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1.0);
  const auto out = through(channel, tone(16000, 3.0), 480);
  const auto steady = std::span(out).subspan(4800, 1u << 17);
  EXPECT_LT(worst_spur_db(steady, 16000 / 1.003, 60), -70);
  double lo = 1e9, hi = 0;
  for (std::size_t i = 0; i + 240 <= steady.size(); i += 240) {
    const double level = rms(steady.subspan(i, 240));
    lo = std::min(lo, level);
    hi = std::max(hi, level);
  }
  EXPECT_LT(db(hi / lo), 0.2) << "level wobble, dB";
}

TEST(Doppler, ATransmitterDrivingAtTheTurtleBotsSpeedShiftsTheToneByVOverC) {
  for (double speed : {0.22, -0.22}) {
    for (bool in_room : {false, true}) {
      ChannelConfig config;
      config.motion = {speed, 0.5, 20};
      if (in_room) config.room.rir_file = rir_path("studio_live_room.wav");
      AcousticChannel channel(kRate, config);
      channel.add_transmitter(3.0);
      const auto out = through(channel, tone(10000, 3.0), 480);
      const auto steady = std::span(out).subspan(24000, 96000);
      // 0.22 m/s is 641 ppm: 6.41 Hz at 10 kHz, down when driving away.
      EXPECT_NEAR(peak_frequency_hz(steady, 9900, 10100), 10000 * (1 - speed / kSpeedOfSoundMps), 1.0)
          << speed << " m/s" << (in_room ? " in a measured room" : " in free field");
    }
  }
}

TEST(Doppler, AMovingTransmitterIsHeardDOverCLateAtOneOverDAndTurnsBackAtItsLimits) {
  // Clicks every 0.25 s from a loudspeaker starting 3 m away, moving away at 2 m/s, turning
  // at 5 m. Heard at time t, a click left at t - d(t)/c.
  ChannelConfig config;
  config.motion = {2.0, 1.0, 5.0};
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(3.0);
  std::vector<float> clicks(kRate * 2, 0.0f);
  for (int k = 0; k < 8; ++k) clicks[static_cast<std::size_t>(k * kRate / 4)] = 1.0f;
  const auto out = through(channel, clicks, 333);
  std::vector<double> level_times_d;
  for (int k = 0; k < 8; ++k) {
    const double sent_s = k * 0.25;
    // d(t) = 3 + 2t until t = 1 s, then 5 - 2(t - 1); solve t - d(t)/c = sent.
    double t = sent_s + 3 / kSpeedOfSoundMps;
    for (int i = 0; i < 20; ++i) {
      const double d = t < 1 ? 3 + 2 * t : 5 - 2 * (t - 1);
      t = sent_s + d / kSpeedOfSoundMps;
    }
    const double d = t < 1 ? 3 + 2 * t : 5 - 2 * (t - 1);
    EXPECT_NEAR(peak_near(out, t * kRate, 5).first, t * kRate, 0.1) << "click " << k;
    const auto window = std::span(out).subspan(static_cast<std::size_t>(t * kRate) - 40, 80);
    // A click lands between samples, so its peak varies; its energy scales as 1/d^2.
    level_times_d.push_back(rms(window) * d);
  }
  const double mean = std::accumulate(level_times_d.begin(), level_times_d.end(), 0.0) / 8;
  for (double v : level_times_d) EXPECT_NEAR(v, mean, 0.05 * mean);
}
