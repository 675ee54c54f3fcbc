#include "reliability/command_frame.h"

#include "reliability/frame_code.h"

namespace dtmf::reliability {

std::uint16_t crc16(std::uint64_t bits, int width) {
  std::uint16_t crc = 0xFFFF;
  for (int i = width - 1; i >= 0; --i) {
    const bool bit = (bits >> i) & 1u;
    const bool top = (crc >> 15) & 1u;
    crc = static_cast<std::uint16_t>(crc << 1);
    if (bit != top) crc ^= 0x1021;
  }
  return crc;
}

namespace {
constexpr int kCheckedBits = kCommandFrameBits - kCommandCrcBits;  // 34
}

std::uint64_t command_frame_pack(const CommandFrame& frame) {
  const std::uint64_t checked =
      (static_cast<std::uint64_t>(frame.address & kAddressMask) << (kSequenceBits + kFramePayloadBits)) |
      (static_cast<std::uint64_t>(frame.sequence & kSequenceMask) << kFramePayloadBits) |
      (frame.payload & kFramePayloadMask);
  return (checked << kCommandCrcBits) | crc16(checked, kCheckedBits);
}

std::optional<CommandFrame> command_frame_unpack(std::uint64_t bits) {
  if (bits >> kCommandFrameBits) return std::nullopt;
  const std::uint64_t checked = bits >> kCommandCrcBits;
  if (crc16(checked, kCheckedBits) != (bits & 0xFFFF)) return std::nullopt;
  return CommandFrame{static_cast<std::uint8_t>((checked >> (kSequenceBits + kFramePayloadBits)) & kAddressMask),
                      static_cast<std::uint8_t>((checked >> kFramePayloadBits) & kSequenceMask),
                      static_cast<std::uint32_t>(checked & kFramePayloadMask)};
}

CodeSymbols command_frame_symbols(std::uint64_t bits) {
  std::array<std::uint8_t, kCodeDataSymbols> data{};
  for (int i = 0; i < kCodeDataSymbols; ++i) {
    data[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(
        (bits >> (kCodeSymbolBits * (kCodeDataSymbols - 1 - i))) & ((1u << kCodeSymbolBits) - 1));
  }
  CodeSymbols symbols{};
  frame_code().encode(data, symbols);
  return symbols;
}

std::uint64_t command_frame_data_bits(std::span<const std::uint8_t> data_symbols) {
  std::uint64_t bits = 0;
  for (int i = 0; i < kCodeDataSymbols; ++i)
    bits = (bits << kCodeSymbolBits) | data_symbols[static_cast<std::size_t>(i)];
  return bits;
}

}  // namespace dtmf::reliability
