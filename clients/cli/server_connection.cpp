#include "server_connection.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "program_main.h"

namespace dtmf::cli {

namespace {
std::string read_text(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(std::string("cannot read the ") + what + " file '" + path + "'");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  return text;
}
}  // namespace

ServerChannel open_server_channel(const ServerOptions& options) {
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (!options.tls_ca.empty()) {
    grpc::SslCredentialsOptions tls;
    tls.pem_root_certs = read_text(options.tls_ca, "TLS certificate");
    credentials = grpc::SslCredentials(tls);
  }
  ServerChannel opened;
  if (!options.token_file.empty()) opened.token = read_text(options.token_file, "token");
  opened.channel = grpc::CreateChannel(options.address, credentials);
  return opened;
}

ServerConnection::ServerConnection(const ServerOptions& options) {
  ServerChannel opened = open_server_channel(options);
  channel_ = std::move(opened.channel);
  token_ = std::move(opened.token);
  if (!channel_->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(5))) {
    throw Unreachable("cannot reach dtmf-server at " + options.address +
                      ": is it running? (start it, or point --server / DTMF_SERVER at it)");
  }
  stub_ = v1::TeleopService::NewStub(channel_);
}

std::unique_ptr<grpc::ClientContext> ServerConnection::context() const {
  auto context = std::make_unique<grpc::ClientContext>();
  if (!token_.empty()) context->AddMetadata("authorization", "Bearer " + token_);
  context->AddMetadata("x-dtmf-client", client_name());
  return context;
}

std::string client_name() {
  // Who calls, for a server that tells another caller who drives the robot.
  char host[256] = "";
  ::gethostname(host, sizeof host - 1);
  const char* user = std::getenv("USER");
  std::string name = std::string("dtmfctl of ") + (user ? user : "someone") + " on " + host;
  // gRPC refuses a call whose metadata value is not printable ASCII.
  for (char& c : name)
    if (c < 0x20 || c > 0x7e) c = '?';
  return name;
}

int exit_code_for(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
      return program::kExitOk;
    case grpc::StatusCode::INVALID_ARGUMENT:
      return program::kExitUsage;
    case grpc::StatusCode::UNAVAILABLE:
      return kExitUnreachable;
    case grpc::StatusCode::UNAUTHENTICATED:
    case grpc::StatusCode::PERMISSION_DENIED:
      return kExitNotAuthorized;
    default:
      return kExitUnconfirmed;
  }
}

bool caller_refused(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::UNAUTHENTICATED ||
         status.error_code() == grpc::StatusCode::PERMISSION_DENIED;
}

std::string describe_status(const grpc::Status& status) {
  if (status.ok()) return "ok";
  return status.error_message().empty() ? "failed (gRPC code " + std::to_string(status.error_code()) + ")"
                                        : status.error_message();
}

}  // namespace dtmf::cli
