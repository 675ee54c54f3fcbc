// Physical layer: audio files in any format the user brings, or a clear refusal.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
#include "support/listen.h"

using namespace dtmf;
using namespace dtmf::physical;
namespace fs = std::filesystem;

namespace {

class WavFileTest : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("dtmf-wav-test-" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

// Writes `frames` of a stereo/mono file at `rate` with libsndfile directly.
void write_raw(const std::string& path, const std::vector<float>& interleaved, int rate, int channels, int format) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = channels;
  info.format = format;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  sf_writef_float(f, interleaved.data(),
                  static_cast<sf_count_t>(interleaved.size() / static_cast<std::size_t>(channels)));
  sf_close(f);
}

std::vector<float> chord_at(int rate, std::uint16_t frame) {
  LinkProfile p = seed_profile();
  p.sample_rate_hz = rate;
  std::vector<float> audio(static_cast<std::size_t>(rate / 2), 0.0f);
  const auto chord = signal::synthesize_frame(p, frame);
  audio.insert(audio.end(), chord.begin(), chord.end());
  audio.resize(audio.size() + static_cast<std::size_t>(rate / 2), 0.0f);
  return audio;
}

std::vector<signal::Heard> hear(const std::vector<float>& audio) {
  auto listener = signal::chord_listener(seed_profile());
  return test_support::listen(listener, audio);
}

}  // namespace

TEST_F(WavFileTest, WriteThenReadGivesTheSamplesBack) {
  const auto audio = chord_at(48000, 0x1234);
  write_wav_file(path("a.wav"), audio, 48000);
  const auto back = read_audio_file(path("a.wav"), 48000);
  ASSERT_EQ(back.size(), audio.size());
  for (std::size_t i = 0; i < audio.size(); i += 97) EXPECT_NEAR(back[i], audio[i], 1.0 / 32768 + 1e-6);
}

TEST_F(WavFileTest, StereoIsMixedDownToMono) {
  const auto mono = chord_at(48000, 0x2345);
  std::vector<float> stereo;
  for (float s : mono) {
    stereo.push_back(s);
    stereo.push_back(s);
  }
  write_raw(path("s.wav"), stereo, 48000, 2, SF_FORMAT_WAV | SF_FORMAT_FLOAT);
  WavFileSource source(path("s.wav"), 48000);
  EXPECT_EQ(source.file_channels(), 2);
  const auto back = read_audio_file(path("s.wav"), 48000);
  ASSERT_EQ(back.size(), mono.size());
  const auto heard = hear(back);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].symbol, 0x2345u);
}

TEST_F(WavFileTest, A44100HzRecordingIsResampledAndStillDecodes) {
  const auto at44 = chord_at(44100, 0xBEEF);
  write_raw(path("r.wav"), at44, 44100, 1, SF_FORMAT_WAV | SF_FORMAT_PCM_24);
  const auto back = read_audio_file(path("r.wav"), 48000, 32001);
  EXPECT_NEAR(static_cast<double>(back.size()), at44.size() * 48000.0 / 44100.0, 48.0);
  const auto heard = hear(back);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].symbol, 0xBEEFu);
}

TEST_F(WavFileTest, ARateTooLowForTheTonesIsRefusedWithTheReason) {
  write_raw(path("low.wav"), std::vector<float>(8000, 0.0f), 8000, 1, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  try {
    WavFileSource source(path("low.wav"), 48000, 32001);
    FAIL() << "8 kHz accepted";
  } catch (const AudioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("8000 Hz"), std::string::npos) << what;
    EXPECT_NE(what.find("48000"), std::string::npos) << what;
  }
}

TEST_F(WavFileTest, NonAudioAndMissingFilesAreRefusedNamingTheFile) {
  std::ofstream(path("text.wav")) << "this is not audio at all\n";
  for (const std::string& name : {path("text.wav"), path("missing.wav")}) {
    try {
      WavFileSource source(name, 48000);
      FAIL() << name;
    } catch (const AudioError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST_F(WavFileTest, AnEmptyRecordingReadsAsNoSamples) {
  write_raw(path("empty.wav"), {}, 48000, 1, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  EXPECT_TRUE(read_audio_file(path("empty.wav"), 48000).empty());
  write_raw(path("empty44.wav"), {}, 44100, 1, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  EXPECT_TRUE(read_audio_file(path("empty44.wav"), 48000).empty());
}

TEST_F(WavFileTest, AnUnwritablePathIsRefusedWithAHint) {
  try {
    WavFileSink sink(path("no/such/folder/x.wav"), 48000);
    FAIL();
  } catch (const AudioError& e) {
    EXPECT_NE(std::string(e.what()).find("folder"), std::string::npos) << e.what();
  }
}
