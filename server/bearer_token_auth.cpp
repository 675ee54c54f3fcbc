#include "bearer_token_auth.h"

#include <arpa/inet.h>
#include <grpcpp/security/auth_metadata_processor.h>
#include <netinet/in.h>
#include <openssl/crypto.h>

#include <stdexcept>
#include <string_view>

namespace dtmf::server {

namespace {

constexpr std::string_view kBearerPrefix = "Bearer ";

class BearerTokenProcessor final : public grpc::AuthMetadataProcessor {
 public:
  explicit BearerTokenProcessor(std::string token) : expected_(std::string(kBearerPrefix) + token) {}

  // A string comparison; no reason to hand it to a thread of its own.
  bool IsBlocking() const override { return false; }

  grpc::Status Process(const InputMetadata& metadata, grpc::AuthContext*, OutputMetadata* consumed,
                       OutputMetadata*) override {
    const auto path = metadata.find(":path");
    if (path != metadata.end() && open_without_token(std::string(path->second.data(), path->second.size()))) {
      return grpc::Status::OK;
    }
    const auto found = metadata.find("authorization");
    if (found != metadata.end() && matches(std::string_view(found->second.data(), found->second.size()))) {
      // Consumed: the token goes no further than this check (not into handlers or logs).
      consumed->insert({"authorization", std::string(found->second.data(), found->second.size())});
      return grpc::Status::OK;
    }
    return {grpc::StatusCode::UNAUTHENTICATED,
            found == metadata.end()
                ? "this server needs a bearer token: send metadata 'authorization: Bearer <token>' "
                  "(dtmfctl --token-file FILE)"
                : "the bearer token in 'authorization' is not this server's: send the token in the file "
                  "given to dtmf-server --auth-token-file (dtmfctl --token-file FILE)"};
  }

 private:
  // In constant time, so that the time to refuse tells nothing about how much of a guess was right.
  bool matches(std::string_view presented) const {
    return presented.size() == expected_.size() &&
           CRYPTO_memcmp(presented.data(), expected_.data(), presented.size()) == 0;
  }

  std::string expected_;
};

}  // namespace

bool open_without_token(const std::string& method_path) {
  return method_path.starts_with("/grpc.health.v1.Health/") || method_path.starts_with("/grpc.reflection.");
}

bool is_loopback_address(const std::string& address) {
  // "localhost" is not an address but a name. By the convention of /etc/hosts (and RFC 6761,
  // which reserves it for loopback) it resolves to 127.0.0.1 and ::1 only, and gRPC listens
  // on what it resolves to; kept, as the name users type.
  if (address == "localhost") return true;
  // Otherwise only a literal address: a name that merely begins with "127." (127.evil.example,
  // 127.0.0.1.nip.io) resolves wherever its owner likes.
  in_addr v4{};
  if (::inet_pton(AF_INET, address.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;  // 127.0.0.0/8
  const std::string v6 = address.size() > 2 && address.front() == '[' && address.back() == ']'
                             ? address.substr(1, address.size() - 2)
                             : address;
  in6_addr six{};
  return ::inet_pton(AF_INET6, v6.c_str(), &six) == 1 && IN6_IS_ADDR_LOOPBACK(&six);  // ::1 only
}

bool open_to_anyone(const ServerSecurity& security, const std::string& address) {
  return !is_loopback_address(address) && (security.tls_cert_pem.empty() || security.auth_token.empty());
}

std::shared_ptr<grpc::ServerCredentials> server_credentials(const ServerSecurity& security,
                                                            const std::string& address) {
  if (security.tls_cert_pem.empty() != security.tls_key_pem.empty()) {
    throw std::invalid_argument("TLS needs both --tls-cert and --tls-key");
  }
  const bool tls = !security.tls_cert_pem.empty();
  if (open_to_anyone(security, address) && !security.allow_anyone_on_the_network && security.auth_token.empty()) {
    throw std::invalid_argument(
        "serving " + address + " without " + (tls ? "a bearer token" : "TLS and a bearer token") +
        " would let anyone who reaches this port drive the robot: add --tls-cert, --tls-key and --auth-token-file, "
        "serve this machine only (--address 127.0.0.1, the default), or accept the risk with "
        "--allow-anyone-on-the-network");
  }
  if (!tls && security.auth_token.empty()) return grpc::InsecureServerCredentials();
  std::shared_ptr<grpc::ServerCredentials> credentials;
  if (tls) {
    grpc::SslServerCredentialsOptions options;
    options.pem_key_cert_pairs.push_back({security.tls_key_pem, security.tls_cert_pem});
    credentials = grpc::SslServerCredentials(options);
  } else if (is_loopback_address(address)) {
    credentials = grpc::experimental::LocalServerCredentials(LOCAL_TCP);
  } else {
    throw std::invalid_argument(
        "--auth-token-file without TLS would let the token cross the network in clear text on " + address +
        ": add --tls-cert and --tls-key, or listen on loopback only (--address 127.0.0.1)");
  }
  if (!security.auth_token.empty()) {
    credentials->SetAuthMetadataProcessor(std::make_shared<BearerTokenProcessor>(security.auth_token));
  }
  return credentials;
}

}  // namespace dtmf::server
