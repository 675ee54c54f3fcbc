// Command abstraction layer: a whole command as the 27-bit payload of one fast frame (the
// seed profile spells commands as words instead).
//
//   bits 26..24  kind: 0 RESET, 1 STOP, 2 DRIVE_FOR_DURATION, 3 TURN_FOR_DURATION,
//                4 DRIVE_FORWARD, 5 TURN; 6 and 7 reserved (docs/protocol.md §10: a velocity
//                command with a lease, and the header of a long, authenticated frame)
//   bits 23..12  field A: speed_percent or rotation_percent, 12 bits (code 0 unused)
//   bits 11..0   field B: duration_s, 12 bits, for the *_FOR_DURATION kinds; else 0
//
// Every field has the 12-bit resolution of the seed's DRIVE_FORWARD word, duration included
// (8 s in 4094 steps of about 2 ms). A payload decodes only when its kind is a command and
// every field is either a valid code or, where the kind has no such field, zero — so a
// command and its parameters take effect together or not at all.
#pragma once

#include <cstdint>

#include "command/word_codec.h"

namespace dtmf::command {

inline constexpr int kPayloadBits = 27;
inline constexpr FieldSpec kDurationField12{"duration_s", 0.0, 8.0, 12};

enum class PayloadKind : std::uint8_t {
  Reset = 0,
  Stop = 1,
  DriveForDuration = 2,
  TurnForDuration = 3,
  DriveForward = 4,
  Turn = 5,
  Velocity = 6,  // reserved
  Extended = 7,  // reserved
};

// Throws ParameterError for an out-of-range parameter.
std::uint32_t encode_payload(const Command& command);

// `command` as the robot will execute it from a payload: encoded and decoded again.
Command quantised_payload(const Command& command);
// The command in `payload`, or an error text naming what does not fit.
ParameterDecode decode_payload(std::uint32_t payload);

}  // namespace dtmf::command
