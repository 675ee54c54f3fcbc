// Reliability layer: the seed profile's CRC-4 frames (SeedFrame).
//
// A seed frame is 16 bits: the 12-bit data word followed by the 4-bit remainder of
// (word << 4) divided by the generator x^4 + x + 1 (binary 10011), computed as the seed's
// long division with XOR (its section 7, Fig. 7). A received frame is intact when dividing
// all 16 bits leaves remainder 0. Example from the seed: 101100101101 -> CRC 1101 ->
// frame 1011001011011101.
#pragma once

#include <cstdint>
#include <string>

namespace dtmf::reliability {

using SeedFrame = std::uint16_t;
using Word = std::uint16_t;  // 12 data bits

inline constexpr unsigned kGenerator = 0b10011;  // x^4 + x + 1
inline constexpr int kCrcBits = 4;
inline constexpr int kSeedFrameBits = 16;

// Remainder of the polynomial division of `bits` (the low `width` bits) by the generator.
std::uint8_t crc_remainder(std::uint32_t bits, int width);
// The CRC of a 12-bit data word.
std::uint8_t crc4(Word word);
// word followed by its CRC.
SeedFrame word_frame_make(Word word);
// True when the frame's 16 bits divide by the generator without remainder.
bool word_frame_intact(SeedFrame frame);
Word word_frame_word(SeedFrame frame);
std::uint8_t word_frame_crc(SeedFrame frame);
// "1011001011011101": `width` bits, most significant first.
std::string bit_string(std::uint64_t bits, int width = kSeedFrameBits);

}  // namespace dtmf::reliability
