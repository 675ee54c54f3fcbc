// The fast profile's authenticated frame at the reliability layer: what its decoder makes of
// noise and of a real frame when the MAC does not hold (no key, or another key). A MAC that
// fails leaves only the CRC-8 behind a decode, so a refusal must keep more of the code for
// detection than an accept does (sealed_frame.h).
#include <gtest/gtest.h>

#include <random>

#include "reliability/sealed_frame.h"

using namespace dtmf::reliability;

namespace {

using Readings = std::array<SymbolReading, kSealedSymbols>;

const SealedCheck kNoKey = [](const FrameBits&) { return false; };

Readings random_tones(std::mt19937& rng) {
  Readings r{};
  for (auto& s : r) s = {static_cast<std::uint8_t>(rng() & 31), 1.0f + static_cast<float>(rng() % 100) / 10.0f, true};
  return r;
}

Readings readings_of(const SealedSymbols& symbols) {
  Readings r{};
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = {symbols[i], 100.0f, true};
  return r;
}

FrameBits a_frame() {
  SealedFrame f;
  f.address = 2;
  f.counter = 311;
  f.payload = 0x5a5a5a5;
  f.mac = 0xdeadbeef;
  return sealed_frame_pack(f);
}

}  // namespace

// Noise read as 24 random tones by a robot that holds no key. Decoded to the code's limit (one
// parity symbol kept), some of them pass the CRC-8: each would be refused and NACKed, a
// "forged frame" out of nothing. With four parity symbols kept for a refusal, none is.
TEST(SealedFrame, NoiseIsNeverReadAsAFrameToRefuse) {
  std::mt19937 rng(17);
  constexpr int kTrials = 100000;
  int refused = 0, crc_holds_at_the_limit = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Readings r = random_tones(rng);
    refused += decode_sealed(r, 7, kNoKey).intact ? 1 : 0;
    std::array<std::uint8_t, kSealedDataSymbols> data{};
    crc_holds_at_the_limit += decode_symbols(r, sealed_code(), 7, kSealedReserveSymbols, data,
                                             [](std::span<const std::uint8_t> d, DecodedSymbols) {
                                               return sealed_frame_unpack(sealed_frame_data_bits(d)).has_value();
                                             })
                                  ? 1
                                  : 0;
  }
  std::printf("random words of 24 tones: %d of %d pass the CRC at the decode limit; %d refused\n",
              crc_holds_at_the_limit, kTrials, refused);
  EXPECT_GE(crc_holds_at_the_limit, 3) << "the sample cannot show the hazard the bound removes";
  EXPECT_EQ(refused, 0);
}

// A real frame under another key: refused when it is heard well enough to tell (two wrong
// tones, or four unheard); with more damage than that it is a damaged frame (NACK), never an
// accept. The MAC's own decode still goes to the limit (seven erased).
TEST(SealedFrame, AFrameUnderAnotherKeyIsRefusedWhileFourParitySymbolsAreKept) {
  const FrameBits bits = a_frame();
  const SealedSymbols clean = sealed_frame_symbols(bits);
  const SealedCheck this_frame = [&](const FrameBits& b) { return b == bits; };

  Readings two_wrong = readings_of(clean);
  for (std::size_t i : {3u, 17u}) two_wrong[i].symbol = static_cast<std::uint8_t>((clean[i] + 9) % 32);
  const auto d = decode_sealed(two_wrong, 7, kNoKey);
  ASSERT_TRUE(d.intact);
  EXPECT_FALSE(d.authentic);
  EXPECT_EQ(d.intact->bits, bits);
  EXPECT_EQ(d.intact->errors, 2);

  Readings four_unheard = readings_of(clean);
  for (std::size_t i : {0u, 6u, 12u, 23u}) four_unheard[i].heard = false;
  ASSERT_TRUE(decode_sealed(four_unheard, 7, kNoKey).intact);

  Readings seven_unheard = readings_of(clean);
  for (std::size_t i : {0u, 2u, 6u, 9u, 12u, 15u, 23u}) seven_unheard[i].heard = false;
  EXPECT_FALSE(decode_sealed(seven_unheard, 7, kNoKey).intact) << "five spent: only the CRC-8 behind it";
  const auto keyed = decode_sealed(seven_unheard, 7, this_frame);
  ASSERT_TRUE(keyed.authentic) << "the MAC stands behind a decode to the limit";
  EXPECT_EQ(keyed.authentic->erasures, 7);
}
