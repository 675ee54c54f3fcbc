// What the gRPC API accepts: every bad value is INVALID_ARGUMENT naming its field, before
// anything reaches the air.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <optional>

#include "command/command.h"
#include "dtmf/v1/teleop.pb.h"
#include "job.h"
#include "reliability/retry_controller.h"

namespace dtmf::server {

struct CommandSettings {
  Policy policy;
  std::chrono::milliseconds decision_timeout;
  const LinkProfile* profile = nullptr;  // nullptr: the transmitter's default
};

// The command a request asks for; throws RequestError.
command::Command drive_command(const v1::DriveRequest& request);
command::Command turn_command(const v1::TurnRequest& request);
// The request's options over the server's defaults; throws RequestError.
CommandSettings command_settings(const v1::CommandOptions& options, const CommandSettings& defaults);
reliability::Decision decision_of(const v1::DecideRequest& request);

// An INVALID_ARGUMENT status waiting to be returned.
class RequestError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
  grpc::Status status() const { return {grpc::StatusCode::INVALID_ARGUMENT, what()}; }
};

}  // namespace dtmf::server
