// Reliability layer: the fast profile's command frame, 50 bits sent as one Reed–Solomon
// codeword of sixteen 5-bit symbols.
//
//   bits 49..47  address (0..7): which robot in the room; 0 is every robot, and the only one
//                sent today (docs/protocol.md §10, "The frame and its reserve")
//   bits 46..43  sequence number (0..15), new for every command the sender sends
//   bits 42..16  payload: the whole command, 27 bits (command/command_payload.h)
//   bits 15..0   CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF) of bits 49..16
//
// The 50 bits are ten 5-bit data symbols, most significant first; RS(16, 10) over GF(32)
// adds six parity symbols (reliability/reed_solomon.h). Each symbol is one 32-ary tone. The
// CRC catches what the code "corrects" into a wrong codeword: a corrupted frame passes both
// with odds far below the CRC's 1 in 65 536, and the non-zero initial value keeps the
// all-zero frame (which a hum could imitate) out of the code.
// Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace dtmf::reliability {

inline constexpr int kCommandFrameBits = 50;
inline constexpr int kAddressBits = 3;
inline constexpr int kSequenceBits = 4;
inline constexpr int kFramePayloadBits = 27;
inline constexpr int kCommandCrcBits = 16;
inline constexpr int kCodeSymbolBits = 5;
inline constexpr int kCodeDataSymbols = kCommandFrameBits / kCodeSymbolBits;  // 10
inline constexpr int kCodeSymbols = 16;
inline constexpr std::uint8_t kSequenceMask = (1u << kSequenceBits) - 1;
inline constexpr std::uint8_t kAddressMask = (1u << kAddressBits) - 1;
inline constexpr std::uint32_t kFramePayloadMask = (1u << kFramePayloadBits) - 1;

struct CommandFrame {
  std::uint8_t address = 0;   // 0..7
  std::uint8_t sequence = 0;  // 0..15
  std::uint32_t payload = 0;  // 27 bits
  bool operator==(const CommandFrame&) const = default;
};

using CodeSymbols = std::array<std::uint8_t, kCodeSymbols>;

// CRC-16/CCITT-FALSE of the low `width` bits of `bits`, most significant first.
std::uint16_t crc16(std::uint64_t bits, int width);

// The 50 bits of `frame` with its CRC.
std::uint64_t command_frame_pack(const CommandFrame& frame);
// The frame in `bits` (50 bits) when its CRC holds.
std::optional<CommandFrame> command_frame_unpack(std::uint64_t bits);

// The frame's codeword: ten data symbols, then six parity symbols.
CodeSymbols command_frame_symbols(std::uint64_t bits);
// The 50 bits of ten data symbols.
std::uint64_t command_frame_data_bits(std::span<const std::uint8_t> data_symbols);

}  // namespace dtmf::reliability
