// Reliability layer: CRC-4 against the seed's worked example and its Table 1 experiment.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>

#include "reliability/crc4.h"

using namespace dtmf::reliability;

namespace {
std::uint32_t bits(const std::string& text) { return static_cast<std::uint32_t>(std::stoul(text, nullptr, 2)); }
}  // namespace

TEST(Crc4, ReproducesTheSeedsWorkedExample) {
  const Word data = static_cast<Word>(bits("101100101101"));
  EXPECT_EQ(data, 2861);
  EXPECT_EQ(crc4(data), bits("1101"));
  EXPECT_EQ(word_frame_make(data), bits("1011001011011101"));
  EXPECT_EQ(bit_string(word_frame_make(data)), "1011001011011101");
  EXPECT_TRUE(word_frame_intact(word_frame_make(data)));
  EXPECT_EQ(word_frame_word(word_frame_make(data)), data);
}

TEST(Crc4, EveryWordMakesAValidFrameAndEverySingleBitErrorIsCaught) {
  for (Word w = 0; w < 4096; ++w) {
    const SeedFrame f = word_frame_make(w);
    ASSERT_TRUE(word_frame_intact(f)) << w;
    for (int bit = 0; bit < 16; ++bit) ASSERT_FALSE(word_frame_intact(static_cast<SeedFrame>(f ^ (1u << bit)))) << w;
  }
}

TEST(Crc4, ExactlyOneFrameInSixteenIsValid) {
  int valid = 0;
  for (std::uint32_t f = 0; f < 65536; ++f) valid += word_frame_intact(static_cast<SeedFrame>(f)) ? 1 : 0;
  EXPECT_EQ(valid, 4096);
}

// The seed's Table 1: for each listed frame, every 4-bit window position (13 of them in 16
// bits) gets all 16 patterns: 208 variants, of which the seed counted 13 accepted.
struct WindowScramble {
  int accepted = 0;
  int rejected = 0;
  int accepted_unchanged = 0;           // accepted variants equal to the listed frame itself
  std::set<SeedFrame> accepted_frames;  // distinct accepted bit patterns
};

WindowScramble scramble(SeedFrame original) {
  WindowScramble result;
  for (int position = 0; position <= 12; ++position) {
    for (unsigned pattern = 0; pattern < 16; ++pattern) {
      const auto variant = static_cast<SeedFrame>((original & ~(0xFu << position)) | (pattern << position));
      if (word_frame_intact(variant)) {
        ++result.accepted;
        result.accepted_frames.insert(variant);
        if (variant == original) ++result.accepted_unchanged;
      } else {
        ++result.rejected;
      }
    }
  }
  return result;
}

TEST(Crc4, SeedTable1WindowScrambleGives13AcceptedAnd195Rejected) {
  const std::array<std::string, 5> listed = {"1011001011011101", "0000001011011110", "0011110101010001",
                                             "1111111000111111", "0010000000001101"};
  for (const std::string& text : listed) {
    const auto frame = static_cast<SeedFrame>(bits(text));
    const WindowScramble r = scramble(frame);
    EXPECT_EQ(r.accepted + r.rejected, 208) << text;
    EXPECT_EQ(r.accepted, 13) << text;
    EXPECT_EQ(r.rejected, 195) << text;
  }
}

TEST(Crc4, Table1AcceptedVariantsAreTheUnchangedFramesNotMissedErrors) {
  // Four listed frames are valid: their 13 "accepted" variants are the frame itself, once per
  // window position (the pattern that rewrites the window with its own bits). No changed
  // frame passes: x^4 + x + 1 catches every error burst of four bits or fewer.
  for (const std::string text : {"1011001011011101", "0000001011011110", "0011110101010001", "0010000000001101"}) {
    const auto frame = static_cast<SeedFrame>(bits(text));
    ASSERT_TRUE(word_frame_intact(frame)) << text;
    const WindowScramble r = scramble(frame);
    EXPECT_EQ(r.accepted_unchanged, 13) << text;
    EXPECT_EQ(r.accepted_frames, std::set<SeedFrame>{frame}) << text;
  }
  // 1111111000111111 is not a valid frame (its data 111111100011 has CRC 1100, not 1111).
  // Its 13 accepted variants are 13 different corrections, one per window position, that
  // land on 8 distinct valid frames.
  const auto invalid = static_cast<SeedFrame>(bits("1111111000111111"));
  EXPECT_FALSE(word_frame_intact(invalid));
  EXPECT_EQ(crc4(word_frame_word(invalid)), bits("1100"));
  const WindowScramble r = scramble(invalid);
  EXPECT_EQ(r.accepted_unchanged, 0);
  EXPECT_EQ(r.accepted_frames.size(), 8u);
}

TEST(Crc4, EveryBurstOfUpToFourBitsIsDetectedForEveryWord) {
  for (Word w = 0; w < 4096; ++w) {
    const SeedFrame f = word_frame_make(w);
    for (int position = 0; position <= 12; ++position) {
      for (unsigned error = 1; error < 16; ++error) {
        ASSERT_FALSE(word_frame_intact(static_cast<SeedFrame>(f ^ (error << position)))) << w << " " << position;
      }
    }
  }
}
