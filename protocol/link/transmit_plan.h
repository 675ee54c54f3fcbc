// A frame as the sender sends, paces and logs it, whatever the profile's format: its bits,
// the tones that carry them, and the audio the loudspeaker plays. Links (link.h) plan them.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "command/command.h"

namespace dtmf::link {

struct TransmitFrame {
  std::optional<command::Word> word;     // word formats: the 12-bit word the frame carries
  std::uint64_t bits = 0;                // the frame as sent, check included
  int bit_count = 0;                     // 16 (seed), 48 (fast), ...
  int check_bit_count = 0;               // the low bits that are the check (CRC)
  std::optional<std::uint8_t> sequence;  // numbered formats: the number its ACK must name
  std::vector<double> tones_hz;          // every tone, chord after chord, in order
  std::vector<float> audio;              // what the loudspeaker plays, tone_ms long
  double tone_ms = 0;                    // sound on air
};

}  // namespace dtmf::link
