// The end-to-end tests' judge of the air (tests/support/air_recording.h): a seed chord cut
// in two by silence is found, with its pieces; whole chords, the gaps between them and an
// ACK played over a chord are not.
#include "support/air_recording.h"

#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/synthesizer.h"

using dtmf::test_support::find_split_chords;

namespace {

const dtmf::LinkProfile& seed = dtmf::seed_profile();
constexpr int kRateHz = 48000;

void append_silence(std::vector<float>& air, double ms) {
  air.resize(air.size() + static_cast<std::size_t>(ms * kRateHz / 1000));
}

void append(std::vector<float>& air, const std::vector<float>& audio) {
  air.insert(air.end(), audio.begin(), audio.end());
}

}  // namespace

TEST(AirRecording, AChordWithAnUnderrunInItIsOneSplitChord) {
  const auto chord = dtmf::signal::synthesize_frame(seed, 0x5a3c);
  ASSERT_EQ(chord.size(), static_cast<std::size_t>(0.8 * kRateHz));
  std::vector<float> air;
  append_silence(air, 500);
  append(air, chord);  // whole
  append_silence(air, 200);
  append(air, std::vector<float>(chord.begin(), chord.begin() + 300 * kRateHz / 1000));  // 300 ms ...
  append_silence(air, 320);                                                              // ... the underrun ...
  append(air, std::vector<float>(chord.begin() + 300 * kRateHz / 1000, chord.end()));    // ... the rest
  append_silence(air, 200);
  append(air, chord);
  append_silence(air, 500);

  const auto split = find_split_chords(air, kRateHz, seed.timing.chord_ms, seed.robot_detector.bandpass_low_hz,
                                       seed.robot_detector.bandpass_high_hz);
  ASSERT_EQ(split.size(), 1u);
  EXPECT_NEAR(split[0].start_s, 1.5, 0.02);
  EXPECT_NEAR(split[0].first_ms, 300, 20);
  EXPECT_NEAR(split[0].gap_ms, 320, 20);
  EXPECT_NEAR(split[0].second_ms, 500, 20);
}

// A sender kept off the CPU lost the time of the hole and played its next chord at once.
TEST(AirRecording, TheRestOfASplitChordMayRunIntoTheNextChord) {
  const auto chord = dtmf::signal::synthesize_frame(seed, 0x5a3c);
  const auto next = dtmf::signal::synthesize_frame(seed, 0x0001);
  std::vector<float> air;
  append_silence(air, 500);
  append(air, std::vector<float>(chord.begin(), chord.begin() + 460 * kRateHz / 1000));
  append_silence(air, 400);
  append(air, std::vector<float>(chord.begin() + 460 * kRateHz / 1000, chord.end()));
  append(air, next);
  append_silence(air, 500);
  const auto split = find_split_chords(air, kRateHz, seed.timing.chord_ms, seed.robot_detector.bandpass_low_hz,
                                       seed.robot_detector.bandpass_high_hz);
  ASSERT_EQ(split.size(), 1u);
  EXPECT_NEAR(split[0].first_ms, 460, 20);
  EXPECT_NEAR(split[0].gap_ms, 400, 20);
  EXPECT_NEAR(split[0].second_ms, 1140, 20);
}

TEST(AirRecording, WholeChordsWithAnAckOverThemAreNotSplit) {
  auto chord = dtmf::signal::synthesize_frame(seed, 0x0000);
  const auto ack = dtmf::signal::synthesize_reply(seed, dtmf::signal::Reply::Ack);
  for (std::size_t i = 0; i < ack.size(); ++i) chord[i + static_cast<std::size_t>(0.15 * kRateHz)] += ack[i];
  std::vector<float> air;
  for (int i = 0; i < 5; ++i) {
    append(air, chord);
    append_silence(air, 200);
  }
  EXPECT_TRUE(find_split_chords(air, kRateHz, seed.timing.chord_ms, seed.robot_detector.bandpass_low_hz,
                                seed.robot_detector.bandpass_high_hz)
                  .empty());
}
