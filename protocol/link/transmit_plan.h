// The sender's frames of a command in either frame format, as the live transmitter sends,
// paces and logs them.
//
//   Word16 (seed):      command -> RESET / mode / parameter words -> one CRC-4 frame and one
//                       four-tone chord each; any ACK answers (sender_path.h).
//   Command48 (fast):   command -> one 48-bit frame with the next sequence number and CRC-16
//                       -> two chords of four 64-ary tones; only ACK(sequence) answers it
//                       (command_frame_path.h).
// Pure: planning allocates the audio but touches no device and no clock.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "command/command.h"
#include "profile/link_profile.h"

namespace dtmf::link {

struct TransmitFrame {
  std::optional<command::Word> word;     // Word16: the 12-bit word the frame carries
  std::uint64_t bits = 0;                // the frame as sent, CRC included
  int bit_count = 0;                     // 16 or 48
  std::optional<std::uint8_t> sequence;  // Command48: the number its ACK must name
  std::vector<double> tones_hz;          // 4 (one chord) or 8 (two chords, in order)
  std::vector<float> audio;              // what the loudspeaker plays, tone_ms long
  double tone_ms = 0;                    // sound on air
};

// The frames of `command` under `profile`, in transmission order. Command48 numbers its
// frame `next_sequence` (or the next number whose chords differ) and advances it past the
// number used; Word16 leaves it alone. Throws command::ParameterError for a bad parameter.
std::vector<TransmitFrame> plan_transmission(const LinkProfile& profile, const command::Command& command,
                                             std::uint8_t& next_sequence);

}  // namespace dtmf::link
