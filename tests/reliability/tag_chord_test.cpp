// The tag chord (reliability/tag_chord.h): its symbols avoid the frame's own tones and their
// neighbours, 9 bands of 16 answer and 8 do not, a band's reading skips what the sender sent,
// the best hypothesis counts, and the bound of docs/security.md follows from the constants.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

#include "reliability/tag_chord.h"

using namespace dtmf::reliability;

namespace {

TagBytes random_tag(std::mt19937& rng) {
  TagBytes t{};
  for (auto& b : t) b = static_cast<std::uint8_t>(rng());
  return t;
}

// Frame symbols as a sealed frame has them: three chords of eight, alternating band sets.
std::vector<std::uint8_t> random_frame(std::mt19937& rng) {
  std::vector<std::uint8_t> symbols(24);
  for (auto& s : symbols) s = static_cast<std::uint8_t>(rng() % kTagChordValues);
  return symbols;
}

// A reading in which every band of every hypothesis hears `symbols` alone.
TagChordReading reading_of(const TagChordSymbols& symbols) {
  TagChordReading r;
  for (auto& hypothesis : r)
    for (auto& band : hypothesis) band.fill(-1);
  for (std::size_t k = 0; k < kTagChordTones; ++k) r[2][k][0] = static_cast<std::int8_t>(symbols[k]);
  return r;
}

}  // namespace

TEST(TagChord, TheFramesOwnTonesAndTheirNeighboursAreTakenInTheirBand) {
  std::vector<std::uint8_t> frame(24, 0);
  frame[0] = 10;   // chord 0, band set 0, band 0
  frame[8] = 31;   // chord 1, band set 1, band 0: band 8
  frame[16] = 0;   // chord 2, band set 0 again, band 0
  frame[13] = 20;  // chord 1, band 5: band 13
  const BandValueSet taken = tag_chord_taken(frame);
  EXPECT_EQ(taken[0], (7u << 9) | 3u) << "9, 10, 11 and 0, 1";
  EXPECT_EQ(taken[8], 3u << 30) << "30, 31: nothing past the band";
  EXPECT_EQ(taken[13], 7u << 19);
}

TEST(TagChord, ItsSymbolsNeverSoundWhereTheFrameRangAndEveryByteIsUsed) {
  std::mt19937 rng(35);
  for (int i = 0; i < 2000; ++i) {
    const BandValueSet taken = tag_chord_taken(random_frame(rng));
    const TagBytes tag = random_tag(rng);
    const TagChordSymbols symbols = tag_chord_symbols(tag, taken);
    for (std::size_t k = 0; k < kTagChordTones; ++k) {
      EXPECT_EQ((taken[k] >> symbols[k]) & 1u, 0u) << "band " << k;
      // At most two frame tones per band (three chords over two band sets), three bins each.
      EXPECT_GE(kTagChordValues - std::popcount(taken[k]), 26);
    }
    EXPECT_TRUE(spells_tag_chord(reading_of(symbols), symbols, taken));
  }
  // Another byte in one band: another symbol there (a free value per byte mod the count).
  const BandValueSet none{};
  TagBytes a{}, b{};
  b[3] = 1;
  EXPECT_NE(tag_chord_symbols(a, none)[3], tag_chord_symbols(b, none)[3]);
  EXPECT_EQ(tag_chord_symbols(a, none)[4], tag_chord_symbols(b, none)[4]);
}

TEST(TagChord, NineBandsAnswerAndEightDoNot) {
  std::mt19937 rng(9);
  const BandValueSet none{};
  const TagChordSymbols tag = tag_chord_symbols(random_tag(rng), none);
  for (int agree = 0; agree <= kTagChordTones; ++agree) {
    TagChordSymbols heard = tag;
    for (int k = agree; k < kTagChordTones; ++k) heard[k] = static_cast<std::uint8_t>((tag[k] + 5) % 32);
    EXPECT_EQ(tag_chord_matches(reading_of(heard), tag, none), agree);
    EXPECT_EQ(spells_tag_chord(reading_of(heard), tag, none), agree >= kTagChordMatchesNeeded) << agree;
  }
  // Unheard bands neither help nor hurt.
  TagChordReading partial = reading_of(tag);
  for (std::size_t k = 9; k < kTagChordTones; ++k) partial[2][k][0] = -1;
  EXPECT_TRUE(spells_tag_chord(partial, tag, none));
  EXPECT_EQ(tag_chord_heard(partial), 9);
}

TEST(TagChord, ABandsReadingSkipsWhatTheSenderSentAndTheBestHypothesisCounts) {
  const BandValueSet none{};
  TagChordSymbols tag{};
  for (std::size_t k = 0; k < kTagChordTones; ++k) tag[k] = static_cast<std::uint8_t>(2 * k);
  BandValueSet sent{};
  TagChordReading r = reading_of(tag);
  for (std::size_t k = 0; k < kTagChordTones; ++k) {
    // The sender's own tail louder than the tag's tone in every band.
    const auto own = static_cast<std::int8_t>((tag[k] + 7) % 32);
    sent[k] = 1u << own;
    r[2][k] = {own, static_cast<std::int8_t>(tag[k]), -1, -1, -1};
  }
  EXPECT_EQ(tag_chord_matches(r, tag, none), 0) << "read plainly, the tail wins";
  EXPECT_EQ(tag_chord_matches(r, tag, sent), 16);
  EXPECT_EQ(tag_chord_plain(r)[0], (tag[0] + 7) % 32);
  // A hypothesis that hears the tag is enough; the others may hear anything.
  TagChordReading shifted = reading_of(tag);
  for (std::size_t k = 0; k < kTagChordTones; ++k) {
    shifted[0][k][0] = static_cast<std::int8_t>((tag[k] + 1) % 32);
    shifted[2][k][0] = k < 10 ? static_cast<std::int8_t>(tag[k]) : -1;
  }
  EXPECT_EQ(tag_chord_matches(shifted, tag, none), 10);
  EXPECT_EQ(tag_chord_plain(shifted)[0], (tag[0] + 1) % 32) << "the hypothesis that heard most";
}

// docs/security.md: a band's free values number at least 26, so one of them stands for at
// most ceil(256 / 26) = 10 bytes of 256; a random reading answers with at most
// sum_{k>=9} C(16,k) p^k (1-p)^(16-k) a hypothesis.
TEST(TagChord, TheForgeryBoundFollowsFromTheConstants) {
  const double p = std::ceil(256.0 / 26) / 256;
  double per_hypothesis = 0;
  for (int k = kTagChordMatchesNeeded; k <= kTagChordTones; ++k) {
    per_hypothesis += std::tgamma(kTagChordTones + 1) / (std::tgamma(k + 1) * std::tgamma(kTagChordTones - k + 1)) *
                      std::pow(p, k) * std::pow(1 - p, kTagChordTones - k);
  }
  const double per_reading = per_hypothesis * kTagChordHypotheses;
  const double readings_an_hour = 3600.0 / 0.01025;  // one a hop
  std::printf("[ figures  ] p %.4f a band, %.2e a hypothesis, %.2e a reading, %.2e an hour\n", p, per_hypothesis,
              per_reading, per_reading * readings_an_hour);
  EXPECT_LT(per_hypothesis, 2.0e-9);
  EXPECT_LT(per_reading * readings_an_hour, 0.01);
  // The best forger plays each band's likeliest free value: a million random such readings
  // against random tags answer none (expected: 1e6 x 9.4e-9 = 0.009).
  std::mt19937 rng(3);
  int answered = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const BandValueSet taken = tag_chord_taken(random_frame(rng));
    const TagChordSymbols tag = tag_chord_symbols(random_tag(rng), taken);
    const TagChordSymbols guess = tag_chord_symbols(TagBytes{}, taken);  // each band's first free value
    answered += spells_tag_chord(reading_of(guess), tag, taken) ? 1 : 0;
  }
  EXPECT_EQ(answered, 0);
}
