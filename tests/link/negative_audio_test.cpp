// What must never become a frame: silence, noise, speech, broken or colliding chords.
// "Accepted" means passed the debouncer and the CRC; none may carry bits that were not sent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "link/seed_sender_path.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "sim/acoustic_channel.h"
#include "support/listen.h"

using namespace dtmf;

namespace {

const LinkProfile& P() { return seed_profile(); }

std::vector<float> noise(const char* kind, double dbfs, double seconds, std::uint64_t seed) {
  sim::ChannelConfig config;
  config.noise = sim::parse_noise(kind, dbfs);
  config.seed = seed;
  return test_support::through_channel(std::vector<float>(static_cast<std::size_t>(seconds * P().sample_rate_hz), 0.0f),
                                       P().sample_rate_hz, 1.0, config, 0);
}

int accepted(const std::vector<link::SeedReceivedFrame>& frames) {
  int n = 0;
  for (const auto& f : frames) n += f.crc_ok ? 1 : 0;
  return n;
}

}  // namespace

TEST(NegativeAudio, SilenceYieldsNothing) {
  EXPECT_TRUE(test_support::receive(P(), std::vector<float>(60 * 48000, 0.0f)).empty());
}

TEST(NegativeAudio, WhiteAndPinkNoiseAloneYieldNoFrame) {
  // Two minutes at each level, from barely audible to louder than the chords themselves.
  std::uint64_t seed = 1;
  for (const char* kind : {"white", "pink"}) {
    for (double dbfs : {-50.0, -30.0, -10.0}) {
      const auto frames = test_support::receive(P(), noise(kind, dbfs, 120, seed++));
      EXPECT_EQ(accepted(frames), 0) << kind << " " << dbfs << " dBFS";
      EXPECT_LE(frames.size(), 1u) << kind << " " << dbfs << " dBFS";
    }
  }
}

TEST(NegativeAudio, SpeechYieldsNoFrame) {
  const std::string path = ::testing::TempDir() + "/speech.wav";
  const std::string text =
      "The quick brown fox jumps over the lazy dog. She sells sea shells by the sea shore. "
      "Peter Piper picked a peck of pickled peppers. Six thick thistle sticks. "
      "Turn left, then drive forward for three seconds, and stop at the red line. "
      "Whistling, hissing and sibilant sounds have most of their energy above four kilohertz.";
  const std::string cmd = "espeak-ng -s 170 -w '" + path + "' \"" + text + "\"";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "espeak-ng is needed (scripts/test installs it)";
  std::vector<float> speech = physical::read_audio_file(path, P().sample_rate_hz);
  ASSERT_GT(speech.size(), 48000u * 10);
  // Loud speech, repeated to about two minutes, then through the room as a speaker 1 m away.
  float peak = 0;
  for (float s : speech) peak = std::max(peak, std::abs(s));
  for (float& s : speech) s *= 0.9f / peak;
  std::vector<float> long_speech;
  while (long_speech.size() < 120u * 48000) long_speech.insert(long_speech.end(), speech.begin(), speech.end());
  const auto frames = test_support::receive(P(), test_support::through_channel(long_speech, P().sample_rate_hz, 1.0));
  EXPECT_EQ(accepted(frames), 0);
  EXPECT_LE(frames.size(), 1u);
}

TEST(NegativeAudio, AChordMissingAnyOneToneYieldsNothing) {
  for (std::uint16_t frame : {std::uint16_t{0x0000}, std::uint16_t{0xB2DD}, std::uint16_t{0xFFFF}}) {
    const signal::Chord chord = signal::chord_for(P().words().tones, frame);
    for (std::size_t missing = 0; missing < 4; ++missing) {
      std::vector<double> three;
      for (std::size_t b = 0; b < 4; ++b)
        if (b != missing) three.push_back(chord[b]);
      std::vector<float> audio(48000, 0.0f);
      const auto sound = signal::synthesize_chord(P(), three, P().timing.chord_ms);
      audio.insert(audio.end(), sound.begin(), sound.end());
      audio.resize(audio.size() + 48000, 0.0f);
      EXPECT_TRUE(test_support::receive(P(), audio).empty()) << frame << " without band " << missing;
    }
  }
}

TEST(NegativeAudio, TwoOverlappingChordsYieldNoWrongFrame) {
  const std::vector<std::pair<std::uint16_t, std::uint16_t>> pairs = {
      {0x1234, 0xABCD}, {0x0000, 0xFFFF}, {0x1234, 0x1235}, {0xB2DD, 0xB3DD}};
  for (auto [a, b] : pairs) {
    for (double level_b : {1.0, 0.5, 0.1}) {
      for (int offset_ms : {0, 300}) {
        std::vector<float> audio(48000 * 3, 0.0f);
        const auto chord_a = signal::chord_for(P().words().tones, a);
        const auto chord_b = signal::chord_for(P().words().tones, b);
        signal::add_chord(std::span(audio).subspan(24000, 38400), chord_a, 0.2, 5, 48000);
        signal::add_chord(std::span(audio).subspan(static_cast<std::size_t>(24000 + offset_ms * 48), 38400), chord_b,
                          0.2 * level_b, 5, 48000);
        for (const auto& f : test_support::receive(P(), audio)) {
          // Where the chords do not overlap, each may be heard on its own; nothing else may.
          EXPECT_TRUE(f.frame == a || f.frame == b)
              << std::hex << a << "+" << b << " heard " << f.frame << std::dec << " level " << level_b;
        }
      }
    }
  }
}
