// What the microphone and loudspeaker do to levels, and steady tones added at the
// microphone: each at the frequency and level asked for.
#include <gtest/gtest.h>

#include <complex>
#include <fstream>

#include "room_test_support.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

// RMS of the component at exactly `hz` (a DFT over whole cycles of it).
double rms_at(std::span<const float> x, double hz) {
  const auto cycles = std::floor(static_cast<double>(x.size()) * hz / kRate);
  const auto n = static_cast<std::size_t>(cycles * kRate / hz);
  std::complex<double> acc = 0;
  for (std::size_t i = 0; i < n; ++i)
    acc += static_cast<double>(x[i]) * std::polar(1.0, -2 * std::numbers::pi * hz * static_cast<double>(i) / kRate);
  return 2 * std::abs(acc) / static_cast<double>(n) / std::sqrt(2.0);
}

// Level of a tone through a channel with these device responses, against a flat one.
double gain_db(const std::string& speaker, const std::string& mic, double hz) {
  auto level = [&](const std::string& s, const std::string& m) {
    ChannelConfig config;
    config.speaker_response = parse_response(s);
    config.mic_response = parse_response(m);
    AcousticChannel channel(kRate, config);
    channel.add_transmitter(1.0);
    const auto out = through(channel, tone(hz, 0.5));
    return rms(std::span(out).subspan(kRate / 10));
  };
  return db(level(speaker, mic) / level("flat", "flat"));
}

std::string error_of(const std::string& text) {
  try {
    parse_response(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(DeviceResponse, TheCheapMicrophoneAttenuatesAsItsBreakpointsSay) {
  const FrequencyResponse cheap = response_preset("cheap-mic");
  EXPECT_DOUBLE_EQ(response_gain_db(cheap, 1000), 0);
  EXPECT_DOUBLE_EQ(response_gain_db(cheap, 16000), -12);
  EXPECT_DOUBLE_EQ(response_gain_db(cheap, 10000), -3);
  for (double hz : {1000.0, 5000.0, 10000.0, 13000.0, 16000.0}) {
    EXPECT_NEAR(gain_db("flat", "cheap-mic", hz), response_gain_db(cheap, hz), 1.0) << hz << " Hz";
  }
  const FrequencyResponse speaker = response_preset("small-speaker");
  for (double hz : {1000.0, 3000.0, 12000.0, 16000.0}) {
    EXPECT_NEAR(gain_db("small-speaker", "flat", hz), response_gain_db(speaker, hz), 1.0) << hz << " Hz";
  }
  // Both together: their decibels add.
  EXPECT_NEAR(gain_db("small-speaker", "cheap-mic", 16000), -27, 1.0);
}

TEST(DeviceResponse, BreakpointsComeFromTextOrAFileAndBadOnesAreNamed) {
  const auto r = parse_response("200:0, 16000:-12");
  ASSERT_EQ(r.points_db.size(), 2u);
  EXPECT_NEAR(response_gain_db(r, std::sqrt(200.0 * 16000)), -6, 1e-9) << "straight on a log-frequency axis";
  const std::string path = ::testing::TempDir() + "/mic.txt";
  std::ofstream(path) << "# a measured microphone\n100 -6\n1000 0\n16000 -9  # top\n";
  EXPECT_DOUBLE_EQ(response_gain_db(parse_response(path), 16000), -9);
  EXPECT_NE(error_of("tin-can").find("neither a preset (flat, cheap-mic, small-speaker)"), std::string::npos);
  EXPECT_NE(error_of("100:-3,abc:2").find("'abc:2' is not a Hz:dB pair"), std::string::npos);
  EXPECT_NE(error_of("100:-3,100:2").find("given twice"), std::string::npos);
  EXPECT_NE(error_of("0:-3").find("must be above 0"), std::string::npos);
  EXPECT_NE(error_of("100:-300").find("between -120 and +40 dB"), std::string::npos);
  EXPECT_TRUE(parse_response("flat").flat());
  EXPECT_EQ(response_fir(parse_response("flat"), kRate), std::vector<float>{1.0f});
  EXPECT_EQ(response_fir(response_preset("cheap-mic"), kRate).size(), static_cast<std::size_t>(kResponseTaps));
}

TEST(Whines, EachIsASteadyToneAtItsFrequencyAndRmsLevel) {
  ChannelConfig config;
  config.whines = {parse_whine("9000:-40"), parse_whine("13333.3:-50")};
  config.seed = 4;
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1.0);
  const std::vector<float> silence(kRate * 4, 0.0f);
  const auto out = through(channel, silence, 1000);
  EXPECT_NEAR(db(rms_at(out, 9000)), -40, 0.05);
  EXPECT_NEAR(db(rms_at(out, 13333.3)), -50, 0.05);
  EXPECT_NEAR(db(rms(out)), 10 * std::log10(1e-4 + 1e-5), 0.05) << "nothing else";
  EXPECT_NEAR(peak_frequency_hz(std::span(out).first(kRate), 8500, 9500), 9000, 0.05);
  EXPECT_NEAR(peak_frequency_hz(std::span(out).subspan(3 * kRate), 13000, 13600), 13333.3, 0.05) << "steady";
  AcousticChannel again(kRate, config);
  again.add_transmitter(1.0);
  EXPECT_EQ(through(again, silence, 777), out) << "the same for a seed, however it is split";
}

TEST(Whines, BadWhinesAreNamed) {
  EXPECT_THROW(parse_whine("9000"), std::invalid_argument);
  EXPECT_THROW(parse_whine("9k:-40"), std::invalid_argument);
  ChannelConfig config;
  config.whines = {{30000, -40}};
  EXPECT_THROW(AcousticChannel(kRate, config), std::invalid_argument);
  config.whines = {{1000, 3}};
  EXPECT_THROW(AcousticChannel(kRate, config), std::invalid_argument);
}
