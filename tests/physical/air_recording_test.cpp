// The end-to-end tests' judge of the air (tests/support/air_recording.h): a seed chord cut
// in two by silence is found, with its pieces (also when its rest runs into the next
// chord); whole chords, the gaps between them and an ACK played over a chord are not.
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

// `chord` with `hole_ms` of silence after its first `at_ms`: an underrun.
void append_with_a_hole(std::vector<float>& air, const std::vector<float>& chord, int at_ms, int hole_ms) {
  const auto at = chord.begin() + at_ms * kRateHz / 1000;
  air.insert(air.end(), chord.begin(), at);
  append_silence(air, hole_ms);
  air.insert(air.end(), at, chord.end());
}

std::vector<dtmf::test_support::SplitChord> split_in(const std::vector<float>& air) {
  return find_split_chords(air, kRateHz, seed.timing.chord_ms, seed.words().robot_detector.bandpass_low_hz,
                           seed.words().robot_detector.bandpass_high_hz);
}

// Exactly one split chord, with these pieces (±20 ms, two of the finder's 10 ms frames).
void expect_one_split(const std::vector<float>& air, double first_ms, double gap_ms, double second_ms) {
  const auto split = split_in(air);
  ASSERT_EQ(split.size(), 1u);
  EXPECT_NEAR(split[0].first_ms, first_ms, 20);
  EXPECT_NEAR(split[0].gap_ms, gap_ms, 20);
  EXPECT_NEAR(split[0].second_ms, second_ms, 20);
}

}  // namespace

TEST(AirRecording, AChordWithAnUnderrunInItIsOneSplitChord) {
  const auto chord = dtmf::signal::synthesize_frame(seed, 0x5a3c);
  ASSERT_EQ(chord.size(), static_cast<std::size_t>(0.8 * kRateHz));
  std::vector<float> air;
  append_silence(air, 500);
  append(air, chord);  // whole
  append_silence(air, 200);
  append_with_a_hole(air, chord, 300, 320);
  append_silence(air, 200);
  append(air, chord);
  append_silence(air, 500);

  expect_one_split(air, 300, 320, 500);
  ASSERT_FALSE(split_in(air).empty());
  EXPECT_NEAR(split_in(air)[0].start_s, 1.5, 0.02);
}

// A sender kept off the CPU lost the time of the hole and played its next chord at once.
TEST(AirRecording, TheRestOfASplitChordMayRunIntoTheNextChord) {
  const auto chord = dtmf::signal::synthesize_frame(seed, 0x5a3c);
  const auto next = dtmf::signal::synthesize_frame(seed, 0x0001);
  std::vector<float> air;
  append_silence(air, 500);
  append_with_a_hole(air, chord, 460, 400);
  append(air, next);
  append_silence(air, 500);
  expect_one_split(air, 460, 400, 1140);
}

// A hole longer than the receiver bridges is found too, and counted apart.
TEST(AirRecording, AHoleLongerThanTheReceiverBridgesIsFoundAndCounted) {
  const auto chord = dtmf::signal::synthesize_frame(seed, 0x5a3c);
  std::vector<float> air;
  append_silence(air, 500);
  append_with_a_hole(air, chord, 300, 900);
  append_silence(air, 200);
  append_with_a_hole(air, chord, 400, 250);
  append_silence(air, 500);
  const auto split = split_in(air);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_NEAR(split[0].gap_ms, 900, 20);
  EXPECT_EQ(dtmf::test_support::holes_longer_than(split, seed.words().debounce.max_dropout_ms), 1);
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
  EXPECT_TRUE(split_in(air).empty());
}
