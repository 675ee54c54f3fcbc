#include "command/command.h"

#include <cstdio>

namespace dtmf::command {

std::string mode_name(Mode mode) {
  switch (mode) {
    case Mode::ModeSelect:
      return "mode_select";
    case Mode::DriveForDuration:
      return "drive_for_duration";
    case Mode::TurnForDuration:
      return "turn_for_duration";
    case Mode::DriveForward:
      return "drive_forward";
    case Mode::Turn:
      return "turn";
    case Mode::Stop:
      return "stop";
  }
  return "unknown";
}

std::optional<Mode> mode_from_word(Word word) {
  if (word >= static_cast<Word>(Mode::ModeSelect) && word <= static_cast<Word>(Mode::Stop)) {
    return static_cast<Mode>(word);
  }
  return std::nullopt;
}

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

struct Describer {
  std::string operator()(const Reset&) const { return "reset"; }
  std::string operator()(const Stop& c) const { return c.every_robot ? "stop every_robot" : "stop"; }
  std::string operator()(const DriveForDuration& c) const {
    return format("drive_for_duration speed=%.1f%% duration=%.2fs", c.speed_percent, c.duration_s);
  }
  std::string operator()(const TurnForDuration& c) const {
    return format("turn_for_duration rotation=%.1f%% duration=%.2fs", c.rotation_percent, c.duration_s);
  }
  std::string operator()(const DriveForward& c) const { return format("drive_forward speed=%.2f%%", c.speed_percent); }
  std::string operator()(const Turn& c) const { return format("turn rotation=%.2f%%", c.rotation_percent); }
  std::string operator()(const Velocity& c) const {
    return format("velocity linear=%+.1f%% angular=%+.1f%% lease=%.2fs", 100 * c.linear_fraction,
                  100 * c.angular_fraction, c.lease_s);
  }
};

struct KindNamer {
  std::string operator()(const Reset&) const { return "reset"; }
  std::string operator()(const Stop&) const { return mode_name(Mode::Stop); }
  std::string operator()(const DriveForDuration&) const { return mode_name(Mode::DriveForDuration); }
  std::string operator()(const TurnForDuration&) const { return mode_name(Mode::TurnForDuration); }
  std::string operator()(const DriveForward&) const { return mode_name(Mode::DriveForward); }
  std::string operator()(const Turn&) const { return mode_name(Mode::Turn); }
  std::string operator()(const Velocity&) const { return "velocity"; }
};

}  // namespace

std::string describe(const Command& command) { return std::visit(Describer{}, command); }
std::string kind_name(const Command& command) { return std::visit(KindNamer{}, command); }

}  // namespace dtmf::command
