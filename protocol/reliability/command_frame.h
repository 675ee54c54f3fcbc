// Reliability layer, part 3: the fast profile's 48-bit command frame.
//
//   bits 47..44  sequence number (0..15), new for every command the sender sends
//   bits 43..16  payload: the whole command, 28 bits (command/command_payload.h)
//   bits 15..0   CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF) of bits 47..16
//
// The frame travels as eight 6-bit symbols, most significant first: symbols 0..3 are the
// first chord's four bands, 4..7 the second's. A corrupted frame passes the CRC with odds of
// about 1 in 65 536 (the seed's CRC-4: 1 in 16), and the non-zero initial value keeps the
// all-zero frame (eight lowest tones, which a hum could imitate) out of the code.
// Pure logic: no I/O, no clock, no allocation.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace dtmf::reliability {

inline constexpr int kCommandFrameBits = 48;
inline constexpr int kCommandSymbols = 8;
inline constexpr int kSymbolBits = 6;
inline constexpr int kSequenceBits = 4;
inline constexpr int kPayloadBits = 28;
inline constexpr int kCommandCrcBits = 16;
inline constexpr std::uint32_t kPayloadMask = (1u << kPayloadBits) - 1;
inline constexpr std::uint8_t kSequenceMask = (1u << kSequenceBits) - 1;

struct CommandFrame {
  std::uint8_t sequence = 0;  // 0..15
  std::uint32_t payload = 0;  // 28 bits
  bool operator==(const CommandFrame&) const = default;
};

using Symbols = std::array<std::uint8_t, kCommandSymbols>;

// CRC-16/CCITT-FALSE of the low `width` bits of `bits`, most significant first.
std::uint16_t crc16(std::uint64_t bits, int width);

// The 48 bits of `frame` with its CRC.
std::uint64_t pack(const CommandFrame& frame);
// The frame in `bits` when its CRC holds.
std::optional<CommandFrame> unpack(std::uint64_t bits);

Symbols to_symbols(std::uint64_t bits);
std::uint64_t from_symbols(const Symbols& symbols);

}  // namespace dtmf::reliability
