#include "command/word_codec.h"
#include "command/overloaded.h"

#include <cmath>
#include <cstdio>

namespace dtmf::command {

namespace {

// Field codes run from 1 to max_code; 0 is never sent (see the header).
Word max_code(const FieldSpec& field) { return static_cast<Word>((1u << field.bits) - 1u); }

std::string range_text(const FieldSpec& field) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g..%g", field.min, field.max);
  return buf;
}

// Two 6-bit fields: duration in bits 11..6, velocity in bits 5..0.
Word pack_pair(Word duration_code, Word velocity_code) {
  return static_cast<Word>((duration_code << 6) | velocity_code);
}

}  // namespace

ParameterError::ParameterError(std::string field, const std::string& message)
    : std::invalid_argument(message), field_(std::move(field)) {}

double field_step(const FieldSpec& field) { return (field.max - field.min) / static_cast<double>(max_code(field) - 1); }

namespace {

// Throws ParameterError naming the field unless `value` lies in its range.
void check_in_range(const FieldSpec& field, double value) {
  if (!std::isfinite(value)) {
    throw ParameterError(field.name, std::string(field.name) + " must be a number in " + range_text(field) + ", got " +
                                         std::to_string(value));
  }
  if (value < field.min || value > field.max) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %g is out of range: allowed %s", field.name, value, range_text(field).c_str());
    throw ParameterError(field.name, buf);
  }
}

}  // namespace

Word encode_field(const FieldSpec& field, double value) {
  check_in_range(field, value);
  const double steps = std::round((value - field.min) / field_step(field));
  return static_cast<Word>(1 + static_cast<Word>(steps));
}

Word encode_field_at_most(const FieldSpec& field, double value) {
  check_in_range(field, value);
  // A hair under a step is that step: 1.0 s must not become 0.875 s through rounding error.
  const double steps = std::floor((value - field.min) / field_step(field) + 1e-9);
  return static_cast<Word>(1 + static_cast<Word>(steps));
}

std::optional<double> decode_field(const FieldSpec& field, Word code) {
  if (code < 1 || code > max_code(field)) return std::nullopt;
  return field.min + (code - 1) * field_step(field);
}

namespace {

struct ParameterEncoder {
  std::optional<Word> operator()(const Reset&) const { return std::nullopt; }
  std::optional<Word> operator()(const Stop& c) const {
    if (c.every_robot)
      throw ParameterError("profile",
                           "a stop for every robot needs a profile whose frames name robots (fast); the seed "
                           "profile's words name none, and every robot that heard one would answer it");
    return std::nullopt;
  }
  std::optional<Word> operator()(const DriveForDuration& c) const {
    return pack_pair(encode_field(kDurationField, c.duration_s), encode_field(kSpeedField6, c.speed_percent));
  }
  std::optional<Word> operator()(const TurnForDuration& c) const {
    return pack_pair(encode_field(kDurationField, c.duration_s), encode_field(kRotationField6, c.rotation_percent));
  }
  std::optional<Word> operator()(const DriveForward& c) const { return encode_field(kSpeedField12, c.speed_percent); }
  std::optional<Word> operator()(const Turn& c) const { return encode_field(kRotationField12, c.rotation_percent); }
  [[noreturn]] std::optional<Word> operator()(const Velocity&) const {
    throw ParameterError("profile",
                         "a velocity command needs a profile with whole-command frames (fast); the seed profile's "
                         "12-bit words cannot carry it");
  }
};

std::optional<Mode> mode_of(const Command& command) {
  using M = std::optional<Mode>;
  return std::visit(Overloaded{[](const Reset&) -> M { return std::nullopt; },
                               [](const DriveForDuration&) -> M { return Mode::DriveForDuration; },
                               [](const TurnForDuration&) -> M { return Mode::TurnForDuration; },
                               [](const DriveForward&) -> M { return Mode::DriveForward; },
                               [](const Turn&) -> M { return Mode::Turn; }, [](const Stop&) -> M { return Mode::Stop; },
                               [](const Velocity&) -> M { return std::nullopt; }},
                    command);
}

}  // namespace

std::optional<Word> parameter_word(const Command& command) { return std::visit(ParameterEncoder{}, command); }

void validate(const Command& command) { (void)parameter_word(command); }

std::vector<Word> encode(const Command& command) {
  std::vector<Word> words{kResetWord};
  if (const auto mode = mode_of(command)) words.push_back(static_cast<Word>(*mode));
  if (const auto parameter = parameter_word(command)) words.push_back(*parameter);
  return words;
}

ParameterDecode decode_parameters(Mode mode, Word word) {
  const Word high = (word >> 6) & 0x3F;
  const Word low = word & 0x3F;
  auto missing = [&](const FieldSpec& field) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "parameter word 0x%03X has no valid %s field for %s", word, field.name,
                  mode_name(mode).c_str());
    return ParameterDecode{std::nullopt, buf};
  };
  switch (mode) {
    case Mode::DriveForDuration: {
      const auto duration = decode_field(kDurationField, high);
      const auto speed = decode_field(kSpeedField6, low);
      if (!duration) return missing(kDurationField);
      if (!speed) return missing(kSpeedField6);
      return {DriveForDuration{*speed, *duration}, {}};
    }
    case Mode::TurnForDuration: {
      const auto duration = decode_field(kDurationField, high);
      const auto rotation = decode_field(kRotationField6, low);
      if (!duration) return missing(kDurationField);
      if (!rotation) return missing(kRotationField6);
      return {TurnForDuration{*rotation, *duration}, {}};
    }
    case Mode::DriveForward: {
      const auto speed = decode_field(kSpeedField12, word);
      if (!speed) return missing(kSpeedField12);
      return {DriveForward{*speed}, {}};
    }
    case Mode::Turn: {
      const auto rotation = decode_field(kRotationField12, word);
      if (!rotation) return missing(kRotationField12);
      return {Turn{*rotation}, {}};
    }
    case Mode::ModeSelect:
    case Mode::Stop:
      break;
  }
  return {std::nullopt, mode_name(mode) + " takes no parameter word"};
}

Command quantised(const Command& command) {
  const auto mode = mode_of(command);
  const auto parameter = parameter_word(command);
  if (!mode || !parameter) return command;
  return *decode_parameters(*mode, *parameter).command;
}

}  // namespace dtmf::command
