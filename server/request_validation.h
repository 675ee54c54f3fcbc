// What the gRPC API accepts: every bad value is INVALID_ARGUMENT naming its field, before
// anything reaches the air or the database. Text a caller sends (labels, notes, ids,
// profile names) must be UTF-8 without NUL or control characters and within a documented
// length (docs/protocol.md §9), so that PostgreSQL never refuses a row the API said OK to.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <optional>
#include <string_view>

#include "command/command.h"
#include "dtmf/v1/teleop.pb.h"
#include "job.h"
#include "reliability/retry_controller.h"

namespace dtmf::server {

struct CommandSettings {
  Policy policy;
  std::chrono::milliseconds decision_timeout;
  const LinkProfile* profile = nullptr;  // nullptr: the transmitter's default
  std::size_t robot = 0;                 // the transmitter's robot (Transmitter::robot_named)
};

// The command a request asks for; throws RequestError.
command::Command drive_command(const v1::DriveRequest& request);
command::Command turn_command(const v1::TurnRequest& request);
// The request's options over the server's defaults; throws RequestError. Checks
// options.robot too: its text (kIdLimit), and that it could be a robot's name
// (robot_name_valid), not that a robot has it: the caller looks it up.
CommandSettings command_settings(const v1::CommandOptions& options, const CommandSettings& defaults);
reliability::Decision decision_of(const v1::DecideRequest& request);

// The limits of a caller's text field, in Unicode characters (code points).
struct TextLimit {
  std::size_t max_chars;
  bool multiline = false;  // tab, line feed and carriage return allowed
};
inline constexpr TextLimit kLabelLimit{100};
inline constexpr TextLimit kNotesLimit{2000, true};
inline constexpr TextLimit kIdLimit{64};  // command_id, run_id (uuids are 36), robot names (32 at most)
inline constexpr TextLimit kProfileLimit{32};

// Throws RequestError naming `field` when `text` is not valid UTF-8, holds a NUL or another
// control character (C0, DEL, C1; in multiline fields tab and line breaks are fine), or is
// longer than the limit.
void check_text(std::string_view field, std::string_view text, TextLimit limit);
// A robot's name in `field`: within kIdLimit, and a name a robot could have (or empty).
void check_robot_name(std::string_view field, const std::string& name);
// A label: check_text, and not empty.
void check_label(std::string_view field, std::string_view label);

// An INVALID_ARGUMENT status waiting to be returned.
class RequestError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
  grpc::Status status() const { return {grpc::StatusCode::INVALID_ARGUMENT, what()}; }
};

}  // namespace dtmf::server
