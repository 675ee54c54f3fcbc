// dtmfctl's live subcommands talk to dtmf-server: how to reach it (address, TLS, token)
// and dtmfctl's exit codes for what comes back.
#pragma once

#include <grpcpp/grpcpp.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "global_options.h"

namespace dtmf::cli {

// 0 confirmed, 2 bad usage (common/program_main.h), and:
inline constexpr int kExitUnconfirmed = 3;  // the robot did not confirm, or the command failed
inline constexpr int kExitUnreachable = 4;  // no server answered
// The server refused the caller before the command: no bearer token or not its token
// (UNAUTHENTICATED), or not allowed (PERMISSION_DENIED). Nothing went on air.
inline constexpr int kExitNotAuthorized = 5;

// Thrown when the server cannot be reached; main() turns it into exit code 4.
class Unreachable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The channel to the server and the token its calls carry, without waiting for the server:
// gRPC connects when first asked, and again after the server restarts (dtmf-console).
struct ServerChannel {
  std::shared_ptr<grpc::Channel> channel;
  std::string token;
};
// Throws std::invalid_argument when a file it names cannot be read.
ServerChannel open_server_channel(const ServerOptions& options);

class ServerConnection {
 public:
  // Connects within a few seconds or throws Unreachable with one clear line.
  explicit ServerConnection(const ServerOptions& options);
  v1::TeleopService::Stub& teleop() { return *stub_; }
  std::shared_ptr<grpc::Channel> channel() const { return channel_; }
  // A context carrying the token, if any.
  std::unique_ptr<grpc::ClientContext> context() const;

 private:
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::TeleopService::Stub> stub_;
  std::string token_;
};

// What dtmfctl calls itself to the server ("dtmfctl of USER on HOST"), sent with every call
// as the metadata x-dtmf-client: a Teleop refused because another stream drives the robot
// names it.
std::string client_name();

// The exit code and the one line to print for a finished call.
int exit_code_for(const grpc::Status& status);
// Whether the server refused the caller (UNAUTHENTICATED, PERMISSION_DENIED): exit code 5.
bool caller_refused(const grpc::Status& status);
std::string describe_status(const grpc::Status& status);

}  // namespace dtmf::cli
