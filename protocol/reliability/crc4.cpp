#include "reliability/crc4.h"

namespace dtmf::reliability {

std::uint8_t crc_remainder(std::uint32_t bits, int width) {
  for (int top = width - 1; top >= kCrcBits; --top) {
    if (bits & (1u << top)) bits ^= kGenerator << (top - kCrcBits);
  }
  return static_cast<std::uint8_t>(bits & 0xF);
}

std::uint8_t crc4(Word word) {
  return crc_remainder(static_cast<std::uint32_t>(word & 0x0FFF) << kCrcBits, kSeedFrameBits);
}

SeedFrame word_frame_make(Word word) { return static_cast<SeedFrame>(((word & 0x0FFF) << kCrcBits) | crc4(word)); }

bool word_frame_intact(SeedFrame frame) { return crc_remainder(frame, kSeedFrameBits) == 0; }

Word word_frame_word(SeedFrame frame) { return static_cast<Word>(frame >> kCrcBits); }

std::uint8_t word_frame_crc(SeedFrame frame) { return static_cast<std::uint8_t>(frame & 0xF); }

std::string bit_string(std::uint64_t bits, int width) {
  std::string text(static_cast<std::size_t>(width), '0');
  for (int i = 0; i < width; ++i) {
    if ((bits >> (width - 1 - i)) & 1u) text[static_cast<std::size_t>(i)] = '1';
  }
  return text;
}

}  // namespace dtmf::reliability
