// Command abstraction layer: commands to 12-bit words and back.
//
// Parameters are quantised into fields of a parameter word (layouts in docs/protocol.md,
// table "Parameter words"): duration and velocity share a word as two 6-bit fields in the
// *_FOR_DURATION modes; DRIVE_FORWARD and TURN give the whole 12 bits to the velocity.
// A field never uses code 0, so no parameter word can equal the RESET word; a field of
// 2^bits - 1 usable codes spans its range in equal steps with both ends and (for the
// rotation) zero exactly representable. Values outside a field's range are refused with an
// error naming the field and its range: nothing is clamped silently.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command/command.h"

namespace dtmf::command {

struct FieldSpec {
  const char* name;  // as in the API: speed_percent, rotation_percent, duration_s
  double min;
  double max;
  int bits;
};

inline constexpr FieldSpec kDurationField{"duration_s", 0.0, 8.0, 6};
inline constexpr FieldSpec kSpeedField6{"speed_percent", 0.0, 100.0, 6};
inline constexpr FieldSpec kRotationField6{"rotation_percent", -100.0, 100.0, 6};
inline constexpr FieldSpec kSpeedField12{"speed_percent", 0.0, 100.0, 12};
inline constexpr FieldSpec kRotationField12{"rotation_percent", -100.0, 100.0, 12};

// An out-of-range or non-finite parameter. what() names the field, the value and the range.
class ParameterError : public std::invalid_argument {
 public:
  ParameterError(std::string field, const std::string& message);
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// The distance between two neighbouring values of a field.
double field_step(const FieldSpec& field);
// value -> code in 1 .. 2^bits - 1 (nearest); throws ParameterError.
Word encode_field(const FieldSpec& field, double value);
// The same, rounded down to the code at or below `value` (for bounds that must not grow).
Word encode_field_at_most(const FieldSpec& field, double value);
// code -> value; codes outside 1 .. 2^bits - 1 give std::nullopt.
std::optional<double> decode_field(const FieldSpec& field, Word code);

// Checks every parameter of `command`; throws ParameterError on the first bad one.
void validate(const Command& command);

// The words that carry `command`, in transmission order: RESET, then mode, then parameters.
// Throws ParameterError.
std::vector<Word> encode(const Command& command);

// The parameter word of a command that has one.
std::optional<Word> parameter_word(const Command& command);

// What a receiver makes of `word` as the parameter of `mode`; an error text if the word is
// not a valid parameter for that mode.
struct ParameterDecode {
  std::optional<Command> command;
  std::string error;
};
ParameterDecode decode_parameters(Mode mode, Word word);

// `command` as the robot will execute it: encoded and decoded again (the quantisation).
Command quantised(const Command& command);

}  // namespace dtmf::command
