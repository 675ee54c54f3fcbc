// Who may call: the server's transport security (plaintext or TLS) and, with a bearer token,
// a check of every call's "authorization: Bearer <token>" metadata before any handler runs.
//
// The check is a gRPC AuthMetadataProcessor: gRPC runs it on each call's initial metadata in
// the transport and answers UNAUTHENTICATED itself, so a call without the token is never
// parsed and never reaches TeleopService (server interceptors cannot refuse a call). gRPC
// accepts a processor only on secure credentials: TLS, or its "local" credentials, which are
// plaintext on the wire but admit loopback peers only. A plaintext server with a token
// therefore listens on loopback; on any other address the token would cross the network in
// clear text, and server_credentials() refuses that with the two ways out.
#pragma once

#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>

namespace dtmf::server {

struct ServerSecurity {
  std::string tls_cert_pem;  // both empty: plaintext
  std::string tls_key_pem;
  std::string auth_token;  // empty: no authentication
};

// Calls that need no token, so that probes and tools find the server: the gRPC health
// service and server reflection (which describes only the public API).
bool open_without_token(const std::string& method_path);

// True for 127.0.0.0/8, ::1 and "localhost" (an --address value, without the port).
bool is_loopback_address(const std::string& address);

// The credentials to listen on `address` with; throws std::invalid_argument when the
// combination cannot be served safely (a token in plaintext off loopback, half a TLS pair).
std::shared_ptr<grpc::ServerCredentials> server_credentials(const ServerSecurity& security, const std::string& address);

}  // namespace dtmf::server
