// Reliability layer: the fast profile's authenticated ("sealed") frame — 80 bits sent as one
// RS(24, 16) codeword over GF(32), twenty-four 32-ary tones on three chords.
//
//   bits 79..77  address (0..7): the robot it is for
//   bit  76      form: 0 a command, 1 a counter synchronisation
//   command:     bits 75..67  the freshness counter's low 9 bits (security/freshness.h)
//                bits 66..40  payload, 27 bits (command/command_payload.h)
//   sync:        bits 75..40  the whole counter, 36 bits
//   bits 39..8   MAC, 32 bits (security/frame_mac.h): address, form, the full counter, payload
//   bits 7..0    CRC-8/AUTOSAR (polynomial 0x2F, initial and final XOR 0xFF) of bits 79..8
//
// The CRC tells a damaged frame (NACK: the sender retransmits) from an intact one whose MAC
// fails (forged, replayed, or under another key: refused); the MAC is what admits a frame.
// Decoding (symbol_decoder.h) keeps one of the eight parity symbols for detection (the
// 50-bit frame keeps two of its six, its CRC-16 being all that stands behind the code): the
// MAC stands behind this one, so the code may correct more (2 errors + erasures <= 7).
// A frame that is refused has no MAC behind it, only the CRC-8: a decode counts as an intact
// frame to refuse only while the code kept four parity symbols for detection (2 errors +
// erasures <= 4). Noise decoded at the limit turns into some codeword one time in 32 and
// passes the CRC one time in 256, a refusal (a NACK from the robot) in every ~8000 tries of a
// window of noise; with four kept it is 2^-20 x 2^-8 a try, below the 50-bit frame's false
// accept (2^-10 x 2^-16). Worse-damaged frames that fail their MAC are NACKed as damaged.
// Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include "reliability/frame_bits.h"
#include "reliability/reed_solomon.h"
#include "reliability/symbol_decoder.h"

namespace dtmf::reliability {

inline constexpr int kSealedFrameBits = 80;
inline constexpr int kSealedSymbols = 24;
inline constexpr int kSealedDataSymbols = 16;
inline constexpr int kSealedCheckBits = 8;  // the CRC; the MAC counts as payload-carried security
inline constexpr int kSealedMacBits = 32;
inline constexpr int kSealedCounterLowBits = 9;
inline constexpr int kSealedSyncCounterBits = 36;
inline constexpr int kSealedReserveSymbols = 1;
inline constexpr int kSealedRefusalReserveSymbols = 4;  // kept when only the CRC stands behind a decode

enum class SealedForm : std::uint8_t { Command = 0, Sync = 1 };

struct SealedFrame {
  std::uint8_t address = 0;
  SealedForm form = SealedForm::Command;
  std::uint64_t counter = 0;  // the low 9 bits (a command) or the whole 36 (a sync), as sent
  std::uint32_t payload = 0;  // a command's 27 bits; 0 for a sync
  std::uint32_t mac = 0;
  bool operator==(const SealedFrame&) const = default;
};

using SealedSymbols = std::array<std::uint8_t, kSealedSymbols>;

// CRC-8/AUTOSAR of the low `width` bits of `bits`, most significant first.
std::uint8_t crc8_autosar(WideBits bits, int width);

FrameBits sealed_frame_pack(const SealedFrame& frame);
// Bits 79..8 of an 80-bit frame, when its CRC-8 holds (every layout in these 80 bits:
// this frame's, and a joint renewal's, renewal_frame.h).
std::optional<WideBits> sealed_checked_body(FrameBits bits);
// `body` (bits 79..8) with its CRC-8 appended.
FrameBits sealed_with_check(WideBits body);
// The frame in `bits` when its CRC holds.
std::optional<SealedFrame> sealed_frame_unpack(FrameBits bits);

const ReedSolomon& sealed_code();
SealedSymbols sealed_frame_symbols(FrameBits bits);
FrameBits sealed_frame_data_bits(std::span<const std::uint8_t> data_symbols);

struct DecodedSealed {
  SealedFrame frame;
  FrameBits bits;
  int erasures = 0;
  int errors = 0;
};
// Whether a frame whose CRC holds is the real thing: its MAC holds (the robot's admission,
// link/frame_admission.h). A damaged frame the code corrects into another codeword passes
// the 8-bit CRC one time in 256; then only its MAC tells, so decoding goes on past it.
using SealedCheck = std::function<bool(const FrameBits& bits)>;
struct SealedDecode {
  std::optional<DecodedSealed> authentic;  // the first decode whose CRC and `authentic` hold
  std::optional<DecodedSealed> intact;     // else the first whose CRC holds with 4 parity kept (forged, other key)
};
// `chase_tones`: as many least certain tones tried with their runner-ups once the erasures
// found nothing authentic (symbol_decoder.h).
SealedDecode decode_sealed(std::span<const SymbolReading, kSealedSymbols> readings, int max_erasures,
                           const SealedCheck& authentic, int chase_tones = 0);
// The hard decision's data symbols, for logs of a frame that did not decode.
FrameBits read_sealed_bits(std::span<const SymbolReading, kSealedSymbols> readings);

}  // namespace dtmf::reliability
