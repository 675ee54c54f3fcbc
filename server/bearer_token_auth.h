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
// Protected mode (in the spirit of Redis's): off loopback the server answers only with TLS
// and a token. Anything less lets whoever reaches the port drive the robot, and needs an
// explicit allow_anyone_on_the_network (dtmf-server --allow-anyone-on-the-network), which
// the program warns about at start.
#pragma once

#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>

namespace dtmf::server {

struct ServerSecurity {
  std::string tls_cert_pem;  // both empty: plaintext
  std::string tls_key_pem;
  std::string auth_token;                    // empty: no authentication
  bool allow_anyone_on_the_network = false;  // serve off loopback without TLS and a token
};

// Whether `security` on `address` lets anyone who reaches the port call it.
bool open_to_anyone(const ServerSecurity& security, const std::string& address);

// Calls that need no token, so that probes and tools find the server: the gRPC health
// service and server reflection (which describes only the public API).
bool open_without_token(const std::string& method_path);

// True for an --address value (without the port) that is this machine only: an IPv4 literal
// in 127.0.0.0/8, the IPv6 literal ::1 (bracketed or not), and the name "localhost". Never
// for another name, however it begins ("127.0.0.1.nip.io" is anyone's).
bool is_loopback_address(const std::string& address);

// The credentials to listen on `address` with; throws std::invalid_argument when the
// combination cannot be served safely (a token in plaintext off loopback, half a TLS pair,
// an unprotected address not explicitly allowed).
std::shared_ptr<grpc::ServerCredentials> server_credentials(const ServerSecurity& security, const std::string& address);

}  // namespace dtmf::server
