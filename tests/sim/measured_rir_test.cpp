// Measured rooms: read at any rate, channel 0 only, trimmed and scaled to a direct sound of
// a unit impulse's energy, with the reverberation times bench/rirs/README.md gives; and what a distance means.
#include <gtest/gtest.h>

#include <sndfile.h>

#include <fstream>

#include "physical/audio_io.h"
#include "room_test_support.h"
#include "sim/measured_rir.h"
#include "sim/room_decay.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

void write_stereo(const std::string& path, const std::vector<float>& left, const std::vector<float>& right, int rate) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = 2;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr);
  std::vector<float> interleaved;
  for (std::size_t i = 0; i < left.size(); ++i) {
    interleaved.push_back(left[i]);
    interleaved.push_back(right[i]);
  }
  sf_writef_float(f, interleaved.data(), static_cast<sf_count_t>(left.size()));
  sf_close(f);
}

std::string error_of(const std::string& path) {
  try {
    load_measured_rir(path, kRate);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(MeasuredRir, EveryRoomLoadsResampledTrimmedToItsDirectSoundWithItsRt60) {
  struct Room {
    const char* file;
    int channels;
    double rt60_s;  // bench/rirs/README.md
    int rate_hz;
  };
  for (const Room& r : {Room{"seminar_room_clap.wav", 1, 0.63, 44100}, Room{"studio_live_room.wav", 2, 0.22, 44100},
                        Room{"smoking_room.wav", 2, 0.76, 44100}, Room{"st_margarets_church.wav", 1, 1.05, 44100},
                        Room{"st_andrews_church.wav", 2, 1.35, 48000}, Room{"monument_chamber.wav", 2, 1.45, 48000},
                        Room{"concert_hall.wav", 1, 1.74, 48000}, Room{"typing_room.wav", 2, 2.08, 48000},
                        Room{"club_hall.wav", 2, 2.24, 44100}}) {
    const MeasuredRir rir = load_measured_rir(rir_path(r.file), kRate);
    EXPECT_EQ(rir.file_rate_hz, r.rate_hz) << r.file;
    EXPECT_EQ(rir.file_channels, r.channels) << r.file;
    EXPECT_LE(rir.direct_index, 16u) << r.file << ": the direct sound a few samples from the start";
    // The direct sound (2.5 ms about its peak) carries a unit impulse's energy, peak positive.
    double direct = 0;
    for (std::size_t i = rir.direct_index >= 48 ? rir.direct_index - 48 : 0; i < rir.direct_index + 72; ++i) {
      direct += static_cast<double>(rir.samples[i]) * rir.samples[i];
    }
    EXPECT_NEAR(direct, 1.0, 1e-3) << r.file;
    EXPECT_GT(rir.samples[rir.direct_index], 0.0f) << r.file;
    for (float s : std::span(rir.samples).first(rir.direct_index))
      EXPECT_LT(std::abs(s), rir.samples[rir.direct_index]) << r.file;
    const auto rt60 = rt60_t20_s(rir.samples, kRate);
    ASSERT_TRUE(rt60) << r.file;
    const auto bands = band_rt60_t20_s(rir.samples, kRate);
    std::printf(
        "[ figures  ] %-22s %.2f s at 48 kHz, RT60 (T20) %.3f s (README %.2f), DRR %.1f dB, T20 1/2/4/8 kHz: %.2f %.2f "
        "%.2f %.2f s\n",
        r.file, static_cast<double>(rir.samples.size()) / kRate, *rt60, r.rt60_s,
        direct_to_reverberant_db(rir.samples, kRate), bands[3].value_or(0), bands[4].value_or(0), bands[5].value_or(0),
        bands[6].value_or(0));
    EXPECT_NEAR(*rt60, r.rt60_s, 0.2 * r.rt60_s) << r.file;
  }
}

TEST(MeasuredRir, AStereoFileAtAnyRateGivesItsChannelZeroNotTheAverage) {
  // Channel 0: a click at 100 samples and an echo; channel 1: a louder click earlier.
  const int rate = 44100;
  std::vector<float> left(rate / 10, 0.0f), right(rate / 10, 0.0f);
  left[100] = -0.5f;  // a microphone of the other polarity: the direct peak still becomes +1
  left[2000] = -0.2f;
  right[50] = 0.9f;
  const std::string path = ::testing::TempDir() + "/stereo_rir.wav";
  write_stereo(path, left, right, rate);
  const MeasuredRir rir = load_measured_rir(path, kRate);
  EXPECT_EQ(rir.file_channels, 2);
  const float peak = rir.samples[rir.direct_index];
  EXPECT_GT(peak, 0.9f) << "a click carries its energy in one sample, resampled in a few";
  // The echo, 1900 samples at 44.1 kHz after the click, is 2068 samples later at 48 kHz, at 0.4.
  const std::size_t echo = rir.direct_index + 2068;
  float near_echo = 0;
  for (std::size_t i = echo - 2; i <= echo + 2; ++i) near_echo = std::max(near_echo, rir.samples[i]);
  EXPECT_NEAR(near_echo / peak, 0.4f, 0.03f);
  // Nothing of the other channel: averaged, its louder click would have been taken for the
  // direct sound and channel 0's would follow 54 samples later.
  for (std::size_t i = rir.direct_index + 30; i < rir.direct_index + 80; ++i)
    EXPECT_LT(std::abs(rir.samples[i]), 0.05f) << i;
}

TEST(MeasuredRir, UnreadableEmptyAndSilentFilesAreRefusedByName) {
  EXPECT_NE(error_of("/nonexistent/room.wav").find("cannot read the room impulse response '/nonexistent/room.wav'"),
            std::string::npos);
  const std::string text = ::testing::TempDir() + "/not_audio.wav";
  std::ofstream(text) << "not audio";
  EXPECT_NE(error_of(text).find("cannot read"), std::string::npos);
  const std::string empty = ::testing::TempDir() + "/empty_rir.wav";
  write_stereo(empty, {}, {}, 48000);
  EXPECT_NE(error_of(empty).find("holds no samples"), std::string::npos);
  const std::string silent = ::testing::TempDir() + "/silent_rir.wav";
  write_stereo(silent, std::vector<float>(1000, 0.0f), std::vector<float>(1000, 0.0f), 48000);
  EXPECT_NE(error_of(silent).find("is silent"), std::string::npos);
}

TEST(MeasuredRir, FartherThanOneMetreOnlyTheDirectSoundFallsAndNothingIsDelayed) {
  // A room's reverberant field is as loud 4 m from the loudspeaker as 1 m from it; the
  // direct sound is 4x (12 dB) weaker.
  ChannelConfig config;
  config.room.rir_file = rir_path("seminar_room_clap.wav");
  AcousticChannel at_1m(kRate, config), at_4m(kRate, config);
  at_1m.add_transmitter(1.0);
  at_4m.add_transmitter(4.0);
  const auto h1 = impulse_response(at_1m, 1.2), h4 = impulse_response(at_4m, 1.2);
  ASSERT_EQ(h1.size(), h4.size());
  // The direct sound where the response has it, its peak there: no delay added.
  const std::size_t direct = at_1m.room()->direct_index();
  const float peak = h1[direct];
  EXPECT_GT(peak, 0.1f) << "the clap's direct sound is smeared over a few samples";
  for (std::size_t i = 0; i < direct + 3; ++i) EXPECT_LE(std::abs(h1[i]), peak + 1e-4f) << i;
  for (std::size_t i = 0; i + 3 < direct; ++i) EXPECT_LT(std::abs(h1[i]), 0.3f * peak) << i;
  EXPECT_NEAR(h4[direct], h1[direct] / 4, 1e-6);
  const auto reverberation_from = direct + static_cast<std::size_t>(kRirDirectAfterS * kRate);
  for (std::size_t i = reverberation_from; i < h1.size(); i += 97) EXPECT_NEAR(h4[i], h1[i], 1e-6) << i;
  // A loudspeaker position means nothing in a measured room.
  EXPECT_THROW(at_1m.add_transmitter_at({1, 1, 1}), std::invalid_argument);
}

TEST(MeasuredRir, NearerThanOneMetreOnlyTheDirectSoundGrows) {
  // A loudspeaker beside its own microphone: its direct sound 10x (0.1 m), the room's
  // reverberant field as loud as from 1 m (it does not grow near the source).
  ChannelConfig config;
  config.room.rir_file = rir_path("smoking_room.wav");
  AcousticChannel at_1m(kRate, config), near(kRate, config);
  at_1m.add_transmitter(1.0);
  near.add_transmitter(0.1);
  const auto h1 = impulse_response(at_1m, 1.2), h01 = impulse_response(near, 1.2);
  ASSERT_EQ(h1.size(), h01.size());
  const std::size_t direct = at_1m.room()->direct_index();
  const auto reverberation_from = direct + static_cast<std::size_t>(kRirDirectAfterS * kRate);
  EXPECT_NEAR(h01[direct], 10 * h1[direct], 1e-5);
  for (std::size_t i = reverberation_from; i < h1.size(); i += 97) EXPECT_NEAR(h01[i], h1[i], 1e-6) << i;
  // Its energy after the direct sound, the room's reverberation, is not 20 dB louder.
  double tail_1m = 0, tail_near = 0;
  for (std::size_t i = reverberation_from; i < h1.size(); ++i) {
    tail_1m += h1[i] * h1[i];
    tail_near += h01[i] * h01[i];
  }
  EXPECT_GT(tail_1m, 0.01) << "the smoking room reverberates";
  EXPECT_NEAR(tail_near / tail_1m, 1.0, 1e-3);
}
