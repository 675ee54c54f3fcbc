// Signal layer: which sets of peaks make a chord or a reply, and which do not.
#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/chord_decoder.h"

using namespace dtmf;
using namespace dtmf::signal;

namespace {
std::vector<Peak> peaks_of(const std::vector<double>& hz) {
  std::vector<Peak> peaks;
  for (double f : hz) peaks.push_back(Peak{f, 0.1});
  return peaks;
}
const TonePlan& plan() { return seed_profile().words().tones; }
const DetectorParams& rules() { return seed_profile().words().robot_detector; }
std::vector<Peak> shifted(std::vector<Peak> peaks, double ppm) {
  for (Peak& p : peaks) p.frequency_hz *= 1.0 + ppm * 1e-6;
  return peaks;
}
}  // namespace

TEST(ChordDecoder, FourPlanTonesMakeTheirFrame) {
  const Chord chord = chord_for(plan(), 0xB2DD);
  const auto match = decode_chord(plan(), peaks_of({chord[2], chord[0], chord[3], chord[1]}), rules());
  ASSERT_TRUE(match);
  EXPECT_EQ(match->frame, 0xB2DD);
  EXPECT_DOUBLE_EQ(match->level, 0.1);
}

TEST(ChordDecoder, QuieterPeaksOffThePlanAndSidelobesOfTheSameToneAreIgnored) {
  const Chord chord = chord_for(plan(), 0x1234);
  std::vector<Peak> peaks = peaks_of({chord[0], chord[0] + 12, chord[1], chord[2], chord[3]});
  for (double hz : {7250.0, 3000.0, 16800.0, 9917.0}) peaks.push_back(Peak{hz, 0.09});
  const auto frame = decode_chord(plan(), peaks, rules());
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame, 0x1234);
}

// The fast profile's chords put eight or sixteen like tones across 4-17.5 kHz; four of
// them may sit on seed plan tones, one per band. A whine or two beside a chord is no crowd.
TEST(ChordDecoder, AChordAmongAsManyOtherTonesAsItsOwnIsRefused) {
  const Chord chord = chord_for(plan(), 0x1234);
  std::vector<Peak> peaks = peaks_of({chord[0], chord[1], chord[2], chord[3], 7250, 9917});  // off the plan
  ASSERT_TRUE(decode_chord(plan(), peaks, rules()));
  peaks.push_back(Peak{15083, 0.1});
  EXPECT_FALSE(decode_chord(plan(), peaks, rules()));
  peaks.back().amplitude = 0.099;  // below the chord's weakest tone: not crowding
  EXPECT_TRUE(decode_chord(plan(), peaks, rules()));
}

// 0.22 m/s of robot motion is 640 ppm; two sound cards add a few hundred more. At 16 kHz,
// 2000 ppm is 32 Hz: beyond the 25 Hz tolerance unless the common offset is found first.
TEST(ChordDecoder, ACommonFrequencyOffsetUpTo3000PpmIsFoundAndReadThrough) {
  const Chord chord = chord_for(plan(), 0xF00F);  // the highest band's highest tone: 16 kHz
  const auto clean = peaks_of({chord[0], chord[1], chord[2], chord[3]});
  for (double ppm : {-3000.0, -2000.0, -640.0, 1500.0, 3000.0}) {
    const auto match = decode_chord(plan(), shifted(clean, ppm), rules());
    ASSERT_TRUE(match) << ppm << " ppm";
    EXPECT_EQ(match->frame, 0xF00F) << ppm << " ppm";
    EXPECT_NEAR(match->offset_ppm, ppm, 800) << ppm << " ppm";
  }
  DetectorParams no_search = rules();
  no_search.max_offset_ppm = 0;
  EXPECT_FALSE(decode_chord(plan(), shifted(clean, -2000), no_search)) << "the test must need the search";
  EXPECT_FALSE(decode_chord(plan(), shifted(clean, -6000), rules())) << "beyond the search: 96 Hz at 16 kHz";
}

TEST(ChordDecoder, TheLevelIsThatOfTheWeakestTone) {
  const Chord chord = chord_for(plan(), 0x4321);
  std::vector<Peak> peaks = {{chord[0], 0.3}, {chord[1], 0.05}, {chord[2], 0.2}, {chord[3], 0.1}};
  EXPECT_DOUBLE_EQ(decode_chord(plan(), peaks, rules())->level, 0.05);
}

TEST(ChordDecoder, AMissingBandMeansNoChord) {
  const Chord chord = chord_for(plan(), 0x1234);
  EXPECT_FALSE(decode_chord(plan(), peaks_of({chord[0], chord[1], chord[2]}), rules()));
  EXPECT_FALSE(decode_chord(plan(), peaks_of({chord[1], chord[2], chord[3]}), rules()));
}

TEST(ChordDecoder, TwoTonesInOneBandMeanNoChord) {
  const Chord a = chord_for(plan(), 0x1234);
  const Chord b = chord_for(plan(), 0x1334);  // differs in band 2 only
  EXPECT_FALSE(decode_chord(plan(), peaks_of({a[0], a[1], a[2], a[3], b[1]}), rules()));
}

// White noise at -31 dBFS (+20 dB SNR) puts peaks near -50 dBFS on plan tones beside a
// chord's -14 dBFS ones: the seed's "one tone per band" rule then threw away most windows.
TEST(ChordDecoder, ANoisePeakFarBelowTheBandsToneIsNoSecondTone) {
  const Chord a = chord_for(plan(), 0x1234);
  const Chord b = chord_for(plan(), 0x1334);
  std::vector<Peak> peaks = {{a[0], 0.2}, {a[1], 0.2}, {a[2], 0.2}, {a[3], 0.2}, {b[1], 0.003}};
  ASSERT_TRUE(decode_chord(plan(), peaks, rules()));
  EXPECT_EQ(decode_chord(plan(), peaks, rules())->frame, 0x1234);
  peaks.back().amplitude = 0.1;  // only 6 dB down: two chords at once
  EXPECT_FALSE(decode_chord(plan(), peaks, rules()));
  peaks.back().amplitude = 0.4;  // the louder tone wins only when it dominates: still two
  EXPECT_FALSE(decode_chord(plan(), peaks, rules()));
}

TEST(ReplyDecoder, AckAndNackNeedBothTonesAndNoneOfTheOther) {
  EXPECT_EQ(decode_reply(plan(), peaks_of({2500, 3500}), 25, 8)->reply, Reply::Ack);
  EXPECT_EQ(decode_reply(plan(), peaks_of({3000, 2000, 1800}), 25, 8)->reply, Reply::Nack);
  EXPECT_FALSE(decode_reply(plan(), peaks_of({2500}), 25, 8));
  EXPECT_FALSE(decode_reply(plan(), peaks_of({2500, 3500, 3000}), 25, 8));
  EXPECT_FALSE(decode_reply(plan(), peaks_of({2500, 3000}), 25, 8));
  EXPECT_FALSE(decode_reply(plan(), peaks_of({2540, 3500}), 25, 8));
  const std::vector<Peak> with_faint_nack = {{2500, 0.4}, {3500, 0.4}, {3000, 0.01}};
  EXPECT_EQ(decode_reply(plan(), with_faint_nack, 25, 8)->reply, Reply::Ack);
}
