#include "request_validation.h"

#include <cmath>

#include "command/word_codec.h"

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

CommandSettings command_settings(const v1::CommandOptions& options, const CommandSettings& defaults) {
  CommandSettings settings = defaults;
  if (options.has_on_unconfirmed()) {
    switch (options.on_unconfirmed()) {
      case v1::UNCONFIRMED_POLICY_ASK: settings.policy = Policy::Ask; break;
      case v1::UNCONFIRMED_POLICY_CONTINUE: settings.policy = Policy::Continue; break;
      case v1::UNCONFIRMED_POLICY_FAIL: settings.policy = Policy::Fail; break;
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
    } catch (const std::invalid_argument& e) {
      throw RequestError(std::string("options.profile: ") + e.what());
    }
  }
  return settings;
}

reliability::Decision decision_of(const v1::DecideRequest& r) {
  if (r.command_id().empty()) throw RequestError("command_id: required (from the AWAITING_DECISION progress)");
  switch (r.decision()) {
    case v1::DECISION_CONTINUE: return reliability::Decision::Continue;
    case v1::DECISION_RETRANSMIT: return reliability::Decision::Retransmit;
    case v1::DECISION_ABORT: return reliability::Decision::GiveUp;
    default:
      throw RequestError("decision: " + std::to_string(r.decision()) +
                         " is not a decision; use DECISION_CONTINUE, DECISION_RETRANSMIT or DECISION_ABORT");
  }
}

}  // namespace dtmf::server
