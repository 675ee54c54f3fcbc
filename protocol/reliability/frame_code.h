// Reliability layer: the fast frame's code, RS(16, 10) over GF(32) (command_frame.h), decoded
// from tones read with unequal certainty (symbol_decoder.h): unheard tones erased first, then
// the least certain, up to `max_erasures`, then (`chase_tones` > 0) the least certain tones
// swapped for their runner-ups; the first decode whose CRC-16 holds is the frame.
// Two of the six parity symbols are kept for detection (2 * errors + erasures <= 4).
// Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "reliability/command_frame.h"
#include "reliability/reed_solomon.h"
#include "reliability/symbol_decoder.h"

namespace dtmf::reliability {

inline constexpr int kCodeReserveSymbols = 2;

// The code itself, shared (libfec's tables are built once).
const ReedSolomon& frame_code();

struct DecodedFrame {
  CommandFrame frame;
  std::uint64_t bits = 0;  // the 50 bits, CRC included
  int erasures = 0;        // symbols erased to decode it
  int errors = 0;          // symbols corrected beyond those
};

std::optional<DecodedFrame> decode_frame(std::span<const SymbolReading, kCodeSymbols> readings, int max_erasures,
                                         int chase_tones = 0);
// The hard decision's data symbols as 50 bits, for logs of a frame that did not decode.
std::uint64_t read_bits(std::span<const SymbolReading, kCodeSymbols> readings);

}  // namespace dtmf::reliability
