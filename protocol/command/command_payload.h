// Command abstraction layer: a whole command as the 27-bit payload of one fast frame (the
// seed profile spells commands as words instead).
//
//   bits 26..24  kind: 0 RESET, 1 STOP, 2 DRIVE_FOR_DURATION, 3 TURN_FOR_DURATION,
//                4 DRIVE_FORWARD, 5 TURN, 6 VELOCITY; 7 reserved (docs/protocol.md §10: the
//                header of a long frame)
//   bits 23..12  field A: speed_percent or rotation_percent, 12 bits (code 0 unused);
//                STOP: 0 this robot, 1 every robot in the room (kEveryRobotField)
//                VELOCITY: linear_fraction -1..1, 12 bits (code 2048 is exactly zero)
//   bits 11..0   field B: duration_s, 12 bits, for the *_FOR_DURATION kinds; else 0;
//                VELOCITY: angular_fraction -1..1 in bits 11..4 (8 bits, code 128 is zero)
//                and lease_s 0.25..2 in bits 3..0 (4 bits)
//
// VELOCITY's steps: 1/2047 of the top speed (0.0001 m/s on a Burger) and 1/127 of the top
// turn rate (0.022 rad/s), finer than turtlebot3_teleop's 0.01 m/s and 0.1 rad/s; the lease
// in 14 steps of 0.125 s, rounded down (kLeaseField4).
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
inline constexpr FieldSpec kLinearFraction12{"linear_fraction", -1.0, 1.0, 12};
inline constexpr FieldSpec kAngularFraction8{"angular_fraction", -1.0, 1.0, 8};
// A lease field carries 0.25..2 s in steps of 0.125 s (15 codes), so that 0.5, 1 and 2 s are
// exact; a lease in between is carried rounded down (encode_field_at_most): the robot never
// holds a velocity longer than its sender asked. Senders ask for kMinLease_s..kMaxLease_s.
inline constexpr FieldSpec kLeaseField4{"lease_s", 0.25, 2.0, 4};
inline constexpr double kMinLease_s = 0.3;
inline constexpr double kMaxLease_s = 2.0;
// STOP's field A for a stop every robot executes, whatever the frame's address.
inline constexpr Word kEveryRobotField = 1;

// The payload's kind field: the fast format's own numbering of the commands, fixed on its
// wire. It is not the seed's mode word (command.h, `Mode`: the seed report's numbering, fixed
// on the seed's wire, with no RESET or VELOCITY and STOP at 6); each format keeps its own, and
// where both number a command alike they are checked to stay so.
enum class PayloadKind : std::uint8_t {
  Reset = 0,
  Stop = 1,
  DriveForDuration = 2,
  TurnForDuration = 3,
  DriveForward = 4,
  Turn = 5,
  Velocity = 6,
  Extended = 7,  // reserved
};
static_assert(static_cast<int>(PayloadKind::DriveForDuration) == static_cast<int>(Mode::DriveForDuration) &&
              static_cast<int>(PayloadKind::TurnForDuration) == static_cast<int>(Mode::TurnForDuration) &&
              static_cast<int>(PayloadKind::DriveForward) == static_cast<int>(Mode::DriveForward) &&
              static_cast<int>(PayloadKind::Turn) == static_cast<int>(Mode::Turn));

// Throws ParameterError for an out-of-range parameter.
std::uint32_t encode_payload(const Command& command);

// `command` as the robot will execute it from a payload: encoded and decoded again.
Command quantised_payload(const Command& command);
// The command in `payload`, or an error text naming what does not fit.
ParameterDecode decode_payload(std::uint32_t payload);

}  // namespace dtmf::command
