// Reliability layer, part 4: eight received symbols to a command frame, with a chase.
//
// The symbols as heard are tried first. When their CRC-16 fails, the `chase_symbols` least
// certain symbols (certainty = the power of a band's best tone over its runner-up; a band
// that did not sound is the least certain of all) are replaced one at a time by their
// runner-up and tried again: at low SNR a wrong symbol is nearly always the runner-up one
// band got wrong, so a single substitution rescues most failed frames. Each extra try is
// an extra chance for a corrupted frame to pass the CRC (1 in 65 536 each), so the chase
// is kept to one substitution at a time and two symbols: three tries in all.
// Pure logic: no I/O, no clock, no allocation.
#pragma once

#include <array>
#include <optional>

#include "reliability/command_frame.h"

namespace dtmf::reliability {

struct SymbolReading {
  Symbols symbols{};
  Symbols runner_up{};
  std::array<float, kCommandSymbols> certainty{};  // best / runner-up power
};

struct ChasedFrame {
  CommandFrame frame;
  std::uint64_t bits = 0;  // as accepted (CRC included)
  int substitutions = 0;   // 0: as heard
};

// The frame the reading carries, if the CRC holds as heard or after one substitution.
std::optional<ChasedFrame> chase_decode(const SymbolReading& reading, int chase_symbols);

}  // namespace dtmf::reliability
