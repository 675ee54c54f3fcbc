// Which credentials a server gets for its flags, and which calls pass without a token.
// (The check itself, through a real gRPC server: server_test.cpp and server_process_test.cpp.)
#include "bearer_token_auth.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "secret_file.h"
#include "support/temp_dir.h"

using namespace dtmf::server;
namespace fs = std::filesystem;

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

// Issue 34: any name that began with "127." counted as loopback, so --address 127.evil.example
// (or 127.0.0.1.nip.io, which resolves wherever its owner likes) was served in clear text
// without a token. Only literal loopback addresses, and the name localhost, count.
TEST(BearerTokenAuth, OnlyLiteralLoopbackAddressesCount) {
  for (const char* address : {"127.0.0.0", "127.255.255.254", "0:0:0:0:0:0:0:1", "[0:0::1]"}) {
    EXPECT_TRUE(is_loopback_address(address)) << address;
  }
  for (const char* address : {"127.evil.example", "127.0.0.1.nip.io", "127.0.0.1.example.com", "127.", "127.1",
                              "127.0.0.256", "127.0.0.1 ", " 127.0.0.1", "127.0.0.1:50051", "0127.0.0.1",
                              "::ffff:10.0.0.1", "::2", "[::1", "::1]", "localhost.evil.example", "128.0.0.1", ""}) {
    EXPECT_FALSE(is_loopback_address(address)) << address;
  }
  // And so a name that only looks like loopback gets the protected-mode refusal.
  EXPECT_TRUE(open_to_anyone({}, "127.evil.example"));
  EXPECT_THROW(server_credentials({}, "127.evil.example"), std::invalid_argument);
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

// The secret files of the server's flags (server/secret_file.h).
namespace {

// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-secret") {}
};

std::string write(const fs::path& file, const std::string& text, mode_t mode) {
  fs::remove(file);
  std::ofstream(file) << text;
  ::chmod(file.c_str(), mode);
  return file.string();
}

// The text of the SecretFileError `read` throws ("" and a failure if it throws none).
template <class Read>
std::string refusal(Read read) {
  try {
    read();
  } catch (const SecretFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "not refused";
  return "";
}

constexpr const char* kToken = "Zq8rT0kenV4lue";

}  // namespace

// Issue 34: an empty token file read as "no token", which turned authentication off.
TEST(SecretFiles, AnEmptyOrBlankTokenFileIsRefusedWithHowToMakeOne) {
  TempDir dir;
  const fs::path file = dir.path / "token";
  for (const std::string blank : {"", "\n", "  \n", " \t\r\n\n", "\r\n"}) {
    const std::string name = write(file, blank, 0600);
    const std::string what = refusal([&] { read_token_file(name); });
    for (const std::string& hint :
         {name, std::string("empty"), "openssl rand -hex 32 > " + name, "chmod 600 " + name}) {
      EXPECT_NE(what.find(hint), std::string::npos) << hint << " in " << what;
    }
    EXPECT_THROW(read_security_files("", "", name), SecretFileError);
  }
  write(file, std::string(kToken) + "\n", 0600);
  EXPECT_EQ(read_token_file(file.string()), kToken);
  EXPECT_EQ(read_security_files("", "", file.string()).auth_token, kToken);
}

// Issue 34: a token file or a TLS key that others could read was accepted; like the link
// key, it is refused with its mode and the chmod that fixes it, and never quoted.
TEST(SecretFiles, ATokenOrTlsKeyOthersMayReadOrWriteIsRefusedWithTheChmodThatFixesIt) {
  TempDir dir;
  const std::string token = write(dir.path / "token", std::string(kToken) + "\n", 0600);
  const std::string key = write(dir.path / "key.pem", std::string("-----BEGIN PRIVATE KEY-----\n") + kToken, 0600);
  const std::string cert = write(dir.path / "cert.pem", "-----BEGIN CERTIFICATE-----\nMIIB\n", 0644);
  for (const mode_t mode : {0644u, 0640u, 0604u, 0620u, 0602u, 0660u, 0666u, 0610u, 0601u}) {
    char octal[8];
    std::snprintf(octal, sizeof octal, "%04o", static_cast<unsigned>(mode));
    for (const std::string& secret : {token, key}) {
      ::chmod(secret.c_str(), mode);
      const std::string what = refusal([&] { read_security_files(cert, key, token); });
      EXPECT_NE(what.find("chmod 600 " + secret), std::string::npos) << what;
      EXPECT_NE(what.find(octal), std::string::npos) << octal << " in " << what;
      EXPECT_EQ(what.find(kToken), std::string::npos) << what;
      EXPECT_EQ(what.find("BEGIN"), std::string::npos) << what;
      ::chmod(secret.c_str(), 0600);
    }
  }
  ::chmod(token.c_str(), 0600);
  ::chmod(key.c_str(), 0400);
  // The certificate is public: 0644 is how it should be.
  const ServerSecurity security = read_security_files(cert, key, token);
  EXPECT_EQ(security.auth_token, kToken);
  EXPECT_EQ(security.tls_key_pem, std::string("-----BEGIN PRIVATE KEY-----\n") + kToken);
  EXPECT_EQ(security.tls_cert_pem, "-----BEGIN CERTIFICATE-----\nMIIB");
  EXPECT_EQ(read_secret_file(key, "TLS key"), security.tls_key_pem);
  // Missing files and empty PEM files are named; a directory is not a secret file.
  EXPECT_NE(refusal([&] { read_security_files(dir.path / "nothing.pem", "", ""); }).find("nothing.pem"),
            std::string::npos);
  EXPECT_NE(refusal([&] { read_token_file((dir.path / "no-token").string()); }).find("no-token"), std::string::npos);
  write(dir.path / "empty.pem", "", 0600);
  EXPECT_NE(refusal([&] { read_security_files("", (dir.path / "empty.pem").string(), ""); }).find("empty"),
            std::string::npos);
  fs::create_directory(dir.path / "dir");
  ::chmod((dir.path / "dir").c_str(), 0700);
  EXPECT_THROW(read_token_file((dir.path / "dir").string()), SecretFileError);
}
