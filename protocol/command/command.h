// Command abstraction layer: the robot commands and the 12-bit words that name them.
//
// A command travels as words: the RESET word, then a mode word, then (for modes that take
// parameters) one parameter word. The numbering of the modes is the table "Mode words" in
// docs/protocol.md; the field layouts are in word_codec.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

namespace dtmf::command {

// 12 data bits; the upper four bits of the type are always zero.
using Word = std::uint16_t;
inline constexpr Word kWordMask = 0x0FFF;

// The RESET word: always returns the receiver to MODE_SELECT, whatever its state.
inline constexpr Word kResetWord = 0x000;

// The seed's mode word (seed report §8): its numbering, fixed on the seed's wire. The fast
// format numbers its payload kinds itself (command_payload.h, `PayloadKind`).
enum class Mode : Word {
  ModeSelect = 1,
  DriveForDuration = 2,
  TurnForDuration = 3,
  DriveForward = 4,
  Turn = 5,
  Stop = 6,
};

struct Reset {};
struct DriveForDuration {
  double speed_percent = 0;  // 0..100
  double duration_s = 0;     // 0..8
};
struct TurnForDuration {
  double rotation_percent = 0;  // -100..100, positive turns left (counter-clockwise)
  double duration_s = 0;        // 0..8
};
struct DriveForward {
  double speed_percent = 0;  // 0..100, until the next command
};
struct Turn {
  double rotation_percent = 0;  // -100..100, until the next command
};
// STOP. `every_robot`: a stop for every robot in the room, whatever its address, which no
// robot answers (docs/protocol.md §10, "A stop for every robot"); only formats whose frames
// name robots carry it (fast).
struct Stop {
  bool every_robot = false;
};
// Live driving (teleop): linear and angular speed together, as fractions of the robot's
// limits (positive: forward, and left / counter-clockwise), held for lease_s unless a newer
// Velocity renews it; then the robot stops by itself. Only profiles with whole-command
// frames carry it (fast); the seed's words cannot.
struct Velocity {
  double linear_fraction = 0;   // -1..1 of the robot's top speed
  double angular_fraction = 0;  // -1..1 of its top turn rate
  double lease_s = 1.0;         // 0.3..2
  bool operator==(const Velocity&) const = default;
};

using Command = std::variant<Reset, DriveForDuration, TurnForDuration, DriveForward, Turn, Stop, Velocity>;

// "drive_for_duration" etc.; the names used in logs, JSON and docs.
std::string mode_name(Mode mode);
// The mode a word names, if it names one.
std::optional<Mode> mode_from_word(Word word);
// "drive_for_duration speed=50.0% duration=3.00s", "velocity linear=+25.0% angular=-10.0% lease=1.00s"
std::string describe(const Command& command);
// "reset", "drive_for_duration", ..., "velocity"
std::string kind_name(const Command& command);
// Whether `command` is for every robot in the room (a Stop with every_robot).
inline bool every_robot(const Command& command) {
  const auto* stop = std::get_if<Stop>(&command);
  return stop && stop->every_robot;
}

}  // namespace dtmf::command
