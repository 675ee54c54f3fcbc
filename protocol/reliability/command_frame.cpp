#include "reliability/command_frame.h"

namespace dtmf::reliability {

namespace {
constexpr std::uint16_t kPolynomial = 0x1021;
constexpr std::uint16_t kInitial = 0xFFFF;
constexpr int kCrcBits = kCommandCrcBits;
constexpr int kCheckedBits = kSequenceBits + kPayloadBits;
}  // namespace

std::uint16_t crc16(std::uint64_t bits, int width) {
  std::uint16_t crc = kInitial;
  for (int i = width - 1; i >= 0; --i) {
    const bool in = (bits >> i) & 1u;
    const bool top = crc & 0x8000u;
    crc = static_cast<std::uint16_t>(crc << 1);
    if (in != top) crc ^= kPolynomial;
  }
  return crc;
}

std::uint64_t pack(const CommandFrame& frame) {
  const std::uint64_t checked = (static_cast<std::uint64_t>(frame.sequence & kSequenceMask) << kPayloadBits) |
                                (frame.payload & kPayloadMask);
  return (checked << kCrcBits) | crc16(checked, kCheckedBits);
}

std::optional<CommandFrame> unpack(std::uint64_t bits) {
  const std::uint64_t checked = (bits >> kCrcBits) & ((std::uint64_t{1} << kCheckedBits) - 1);
  if ((bits >> kCommandFrameBits) != 0 || crc16(checked, kCheckedBits) != (bits & 0xFFFFu)) return std::nullopt;
  return CommandFrame{static_cast<std::uint8_t>(checked >> kPayloadBits),
                      static_cast<std::uint32_t>(checked & kPayloadMask)};
}

Symbols to_symbols(std::uint64_t bits) {
  Symbols symbols{};
  for (int i = 0; i < kCommandSymbols; ++i) {
    symbols[static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>((bits >> ((kCommandSymbols - 1 - i) * kSymbolBits)) & 0x3F);
  }
  return symbols;
}

std::uint64_t from_symbols(const Symbols& symbols) {
  std::uint64_t bits = 0;
  for (const std::uint8_t s : symbols) bits = (bits << kSymbolBits) | (s & 0x3F);
  return bits;
}

}  // namespace dtmf::reliability
