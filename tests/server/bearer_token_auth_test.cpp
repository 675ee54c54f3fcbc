// Which credentials a server gets for its flags, and which calls pass without a token.
// (The check itself, through a real gRPC server: server_test.cpp and server_process_test.cpp.)
#include "bearer_token_auth.h"

#include <gtest/gtest.h>

using namespace dtmf::server;

TEST(BearerTokenAuth, OnlyHealthAndReflectionPassWithoutAToken) {
  EXPECT_TRUE(open_without_token("/grpc.health.v1.Health/Check"));
  EXPECT_TRUE(open_without_token("/grpc.health.v1.Health/Watch"));
  EXPECT_TRUE(open_without_token("/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo"));
  EXPECT_TRUE(open_without_token("/grpc.reflection.v1.ServerReflection/ServerReflectionInfo"));
  EXPECT_FALSE(open_without_token("/dtmf.v1.TeleopService/Drive"));
  EXPECT_FALSE(open_without_token("/dtmf.v1.TeleopService/GetReport"));
  EXPECT_FALSE(open_without_token("/grpc.health.v1.HealthX/Check"));  // a look-alike service
  EXPECT_FALSE(open_without_token(""));
}

TEST(BearerTokenAuth, LoopbackAddresses) {
  for (const char* address : {"127.0.0.1", "127.1.2.3", "localhost", "::1", "[::1]"}) {
    EXPECT_TRUE(is_loopback_address(address)) << address;
  }
  for (const char* address : {"0.0.0.0", "::", "[::]", "192.0.2.2", "robot.local", "1127.0.0.1"}) {
    EXPECT_FALSE(is_loopback_address(address)) << address;
  }
}

namespace {
ServerSecurity with(std::string cert, std::string key, std::string token) {
  ServerSecurity security;
  security.tls_cert_pem = std::move(cert);
  security.tls_key_pem = std::move(key);
  security.auth_token = std::move(token);
  return security;
}
}  // namespace

TEST(BearerTokenAuth, ATokenInClearTextIsServedOnLoopbackOnly) {
  EXPECT_NE(server_credentials({}, "127.0.0.1"), nullptr);                 // plaintext, this machine only
  EXPECT_NE(server_credentials(with("", "", "t"), "127.0.0.1"), nullptr);  // local credentials
  try {
    server_credentials(with("", "", "t"), "0.0.0.0");
    FAIL() << "a token in clear text on 0.0.0.0 was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string text = e.what();
    for (const char* hint : {"0.0.0.0", "--tls-cert", "--address 127.0.0.1"}) {
      EXPECT_NE(text.find(hint), std::string::npos) << hint << " in " << text;
    }
  }
  EXPECT_THROW(server_credentials(with("x", "", ""), "0.0.0.0"), std::invalid_argument);
  EXPECT_THROW(server_credentials(with("", "x", ""), "0.0.0.0"), std::invalid_argument);
}

// Protected mode: off loopback, only TLS with a token is served unless the risk is named.
TEST(BearerTokenAuth, AnotherAddressWithoutTlsAndATokenNeedsTheFlagThatNamesTheRisk) {
  for (const ServerSecurity& open : {ServerSecurity{}, with("cert", "key", "")}) {
    EXPECT_TRUE(open_to_anyone(open, "0.0.0.0"));
    try {
      server_credentials(open, "0.0.0.0");
      FAIL() << "served 0.0.0.0 to anyone without being told to";
    } catch (const std::invalid_argument& e) {
      const std::string text = e.what();
      for (const char* hint : {"anyone", "--allow-anyone-on-the-network", "--auth-token-file", "--address 127.0.0.1"})
        EXPECT_NE(text.find(hint), std::string::npos) << hint << " in " << text;
    }
  }
  ServerSecurity allowed;
  allowed.allow_anyone_on_the_network = true;
  EXPECT_NE(server_credentials(allowed, "0.0.0.0"), nullptr);
  EXPECT_FALSE(open_to_anyone({}, "127.0.0.1"));
  EXPECT_FALSE(open_to_anyone({}, "::1"));
}
