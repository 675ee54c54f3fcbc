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
const TonePlan& plan() { return seed_profile().tones; }
}  // namespace

TEST(ChordDecoder, FourPlanTonesMakeTheirFrame) {
  const Chord chord = chord_for(plan(), 0xB2DD);
  const auto match = decode_chord(plan(), peaks_of({chord[2], chord[0], chord[3], chord[1]}), 25, 8);
  ASSERT_TRUE(match);
  EXPECT_EQ(match->frame, 0xB2DD);
  EXPECT_DOUBLE_EQ(match->level, 0.1);
}

TEST(ChordDecoder, PeaksOffThePlanAndSidelobesOfTheSameToneAreIgnored) {
  const Chord chord = chord_for(plan(), 0x1234);
  const auto frame = decode_chord(
      plan(), peaks_of({chord[0], chord[0] + 12, chord[1], chord[2], chord[3], 7250, 3000, 16800}), 25, 8);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame, 0x1234);
}

TEST(ChordDecoder, TheLevelIsThatOfTheWeakestTone) {
  const Chord chord = chord_for(plan(), 0x4321);
  std::vector<Peak> peaks = {{chord[0], 0.3}, {chord[1], 0.05}, {chord[2], 0.2}, {chord[3], 0.1}};
  EXPECT_DOUBLE_EQ(decode_chord(plan(), peaks, 25, 8)->level, 0.05);
}

TEST(ChordDecoder, AMissingBandMeansNoChord) {
  const Chord chord = chord_for(plan(), 0x1234);
  EXPECT_FALSE(decode_chord(plan(), peaks_of({chord[0], chord[1], chord[2]}), 25, 8));
  EXPECT_FALSE(decode_chord(plan(), peaks_of({chord[1], chord[2], chord[3]}), 25, 8));
}

TEST(ChordDecoder, TwoTonesInOneBandMeanNoChord) {
  const Chord a = chord_for(plan(), 0x1234);
  const Chord b = chord_for(plan(), 0x1334);  // differs in band 2 only
  EXPECT_FALSE(decode_chord(plan(), peaks_of({a[0], a[1], a[2], a[3], b[1]}), 25, 8));
}

// White noise at -31 dBFS (+20 dB SNR) puts peaks near -50 dBFS on plan tones beside a
// chord's -14 dBFS ones: the seed's "one tone per band" rule then threw away most windows.
TEST(ChordDecoder, ANoisePeakFarBelowTheBandsToneIsNoSecondTone) {
  const Chord a = chord_for(plan(), 0x1234);
  const Chord b = chord_for(plan(), 0x1334);
  std::vector<Peak> peaks = {{a[0], 0.2}, {a[1], 0.2}, {a[2], 0.2}, {a[3], 0.2}, {b[1], 0.003}};
  ASSERT_TRUE(decode_chord(plan(), peaks, 25, 8));
  EXPECT_EQ(decode_chord(plan(), peaks, 25, 8)->frame, 0x1234);
  peaks.back().amplitude = 0.1;  // only 6 dB down: two chords at once
  EXPECT_FALSE(decode_chord(plan(), peaks, 25, 8));
  peaks.back().amplitude = 0.4;  // the louder tone wins only when it dominates: still two
  EXPECT_FALSE(decode_chord(plan(), peaks, 25, 8));
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
