#include "request_validation.h"

#include <utf8cpp/utf8.h>

#include <cmath>
#include <cstdio>

#include "command/word_codec.h"
#include "robot_roster.h"
#include "shown_text.h"

namespace dtmf::server {

namespace {

// The codec names the field and the range; bad values never reach the queue.
command::Command checked(const command::Command& command) {
  try {
    command::validate(command);
  } catch (const command::ParameterError& e) {
    throw RequestError(e.what());
  }
  return command;
}

}  // namespace

command::Command drive_command(const v1::DriveRequest& r) {
  if (r.has_duration_s()) return checked(command::DriveForDuration{r.speed_percent(), r.duration_s()});
  return checked(command::DriveForward{r.speed_percent()});
}

command::Command turn_command(const v1::TurnRequest& r) {
  if (r.has_duration_s()) return checked(command::TurnForDuration{r.rotation_percent(), r.duration_s()});
  return checked(command::Turn{r.rotation_percent()});
}

void check_text(std::string_view field, std::string_view text, TextLimit limit) {
  const std::string name(field);
  if (!utf8::is_valid(text.begin(), text.end())) {
    throw RequestError(name + ": not valid UTF-8 (send text as UTF-8)");
  }
  std::size_t chars = 0;
  for (auto it = text.begin(); it != text.end(); ++chars) {
    const std::uint32_t c = utf8::unchecked::next(it);
    if (c == 0) throw RequestError(name + ": holds a NUL character (U+0000), which cannot be stored; remove it");
    const bool line_control = c == '\t' || c == '\n' || c == '\r';
    if ((c < 0x20 && !(limit.multiline && line_control)) || (c >= 0x7f && c < 0xa0)) {
      char code[16];
      std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(c));
      throw RequestError(name + ": holds the control character " + code + (limit.multiline ? "" : " (one line only)") +
                         "; remove it");
    }
  }
  if (chars > limit.max_chars) {
    throw RequestError(name + ": " + std::to_string(chars) + " characters, at most " + std::to_string(limit.max_chars) +
                       " allowed");
  }
}

void check_label(std::string_view field, std::string_view label) {
  if (label.empty()) throw RequestError(std::string(field) + ": name the run, e.g. general, noise or 4 m");
  check_text(field, label, kLabelLimit);
}

void check_robot_name(std::string_view field, const std::string& name) {
  check_text(field, name, kIdLimit);
  // A name no robot can have is refused here, shown: the lookup's refusal prints the name as it is.
  if (!name.empty() && !robot_name_valid(name)) {
    throw RequestError(std::string(field) + ": " + shown(name) +
                       " is no robot's name (1 to 32 letters, digits, - or _; dtmfctl robots lists them)");
  }
}

CommandSettings command_settings(const v1::CommandOptions& options, const CommandSettings& defaults) {
  check_text("options.profile", options.profile(), kProfileLimit);
  check_robot_name("options.robot", options.robot());
  CommandSettings settings = defaults;
  if (options.has_on_unconfirmed()) {
    switch (options.on_unconfirmed()) {
      case v1::UNCONFIRMED_POLICY_ASK:
        settings.policy = Policy::Ask;
        break;
      case v1::UNCONFIRMED_POLICY_CONTINUE:
        settings.policy = Policy::Continue;
        break;
      case v1::UNCONFIRMED_POLICY_FAIL:
        settings.policy = Policy::Fail;
        break;
      default:
        throw RequestError("options.on_unconfirmed: " + std::to_string(options.on_unconfirmed()) +
                           " is not a policy; use UNCONFIRMED_POLICY_ASK, _CONTINUE or _FAIL, or leave it out");
    }
  }
  const double timeout_s = options.decision_timeout_s();
  if (!std::isfinite(timeout_s) || timeout_s < 0 || timeout_s > 3600) {
    throw RequestError("options.decision_timeout_s: must be 0..3600 seconds (0: the server's default), got " +
                       std::to_string(timeout_s));
  }
  if (timeout_s > 0) settings.decision_timeout = std::chrono::milliseconds(static_cast<long>(timeout_s * 1000));
  if (!options.profile().empty()) {
    try {
      settings.profile = &profile_by_name(options.profile());
    } catch (const std::invalid_argument&) {  // its text holds the name as it is: not shown
      throw RequestError("options.profile: " + shown(options.profile()) + " is no profile; choose one of " +
                         profile_names());
    }
  }
  return settings;
}

reliability::Decision decision_of(const v1::DecideRequest& r) {
  if (r.command_id().empty()) throw RequestError("command_id: required (from the AWAITING_DECISION progress)");
  check_text("command_id", r.command_id(), kIdLimit);
  switch (r.decision()) {
    case v1::DECISION_CONTINUE:
      return reliability::Decision::Continue;
    case v1::DECISION_RETRANSMIT:
      return reliability::Decision::Retransmit;
    case v1::DECISION_ABORT:
      return reliability::Decision::GiveUp;
    default:
      throw RequestError("decision: " + std::to_string(r.decision()) +
                         " is not a decision; use DECISION_CONTINUE, DECISION_RETRANSMIT or DECISION_ABORT");
  }
}

}  // namespace dtmf::server
