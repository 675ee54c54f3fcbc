// Reliability layer: the fast frame's code, RS(16, 10) over GF(32) (command_frame.h), and its
// decoding from tones read with unequal certainty.
//
// The listener reads each of the sixteen tones as a symbol with a certainty (how far its bin
// stood above the runner-up) and a flag for tones it could not hear at all (no bin stood out,
// or the bin did not rise when the chord began: a reverberant tail). Decoding tries the
// codeword with the unheard tones erased, then with the least certain heard tones erased too,
// one more at a time, up to `max_erasures`; the first decode whose CRC holds is the frame.
// Two of the six parity symbols are kept for detection (2 * errors + erasures <= 4): pushed
// to its limit, the code turns noise into some codeword and only the CRC would be left to
// refuse it. Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "reliability/command_frame.h"
#include "reliability/reed_solomon.h"

namespace dtmf::reliability {

inline constexpr int kCodeReserveSymbols = 2;

// The code itself, shared (libfec's tables are built once).
const ReedSolomon& frame_code();

struct SymbolReading {
  std::uint8_t symbol = 0;  // the strongest tone of its band
  float certainty = 1;      // its power over the runner-up's (>= 1)
  bool heard = true;        // false: erase it
};

struct DecodedFrame {
  CommandFrame frame;
  std::uint64_t bits = 0;  // the 50 bits, CRC included
  int erasures = 0;        // symbols erased to decode it
  int errors = 0;          // symbols corrected beyond those
};

std::optional<DecodedFrame> decode_frame(std::span<const SymbolReading, kCodeSymbols> readings, int max_erasures);
// The hard decision's data symbols as 50 bits, for logs of a frame that did not decode.
std::uint64_t read_bits(std::span<const SymbolReading, kCodeSymbols> readings);

}  // namespace dtmf::reliability
