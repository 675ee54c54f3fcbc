#include "secret_file.h"

#include "security/owned_file.h"

#include <fcntl.h>
#include <openssl/crypto.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace dtmf::server {

namespace {

using security::FileDescriptor;
using security::octal_mode;

constexpr std::size_t kMaxFileBytes = 1 << 20;  // a token or a PEM file is far smaller

// Wipes a string's bytes when it goes out of scope unreturned (a refused secret).
struct Wipe {
  std::string& text;
  bool keep = false;
  ~Wipe() {
    if (!keep) OPENSSL_cleanse(text.data(), text.size());
  }
};

// Reads `path`; with `secret`, refuses it unless only its owner may read or write it, checked
// on the open file before a byte is read. Errors name the file, never its content.
std::string read_file(const std::string& path, const char* what, bool secret) {
  const std::string file = std::string("the ") + what + " file '" + path + "'";
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw SecretFileError("cannot read " + file + ": " + std::strerror(errno));
  const FileDescriptor open_file(fd);
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw SecretFileError("cannot read " + file + ": " + std::strerror(errno));
  // A pipe (--auth-token-file <(...)) is fine; a directory or a device is not what was meant.
  if (!S_ISREG(info.st_mode) && !S_ISFIFO(info.st_mode)) throw SecretFileError(file + " is not a regular file");
  if (secret && (info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw SecretFileError(file + " may be read or changed by others (mode " + octal_mode(info.st_mode) +
                          "); allow its owner only: chmod 600 " + path);
  }
  std::string text;
  Wipe wipe{text};
  if (S_ISREG(info.st_mode) && info.st_size >= 0 && static_cast<std::size_t>(info.st_size) <= kMaxFileBytes) {
    text.reserve(static_cast<std::size_t>(info.st_size) + 1);  // no reallocation leaves copies behind
  }
  std::array<char, 4096> chunk{};
  while (true) {
    const ssize_t got = ::read(fd, chunk.data(), chunk.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      OPENSSL_cleanse(chunk.data(), chunk.size());
      throw SecretFileError("cannot read " + file + ": " + std::strerror(error));
    }
    if (got == 0) break;
    text.append(chunk.data(), static_cast<std::size_t>(got));
    if (text.size() > kMaxFileBytes) {
      OPENSSL_cleanse(chunk.data(), chunk.size());
      throw SecretFileError(file + " is longer than 1 MiB: is it the right file?");
    }
  }
  OPENSSL_cleanse(chunk.data(), chunk.size());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) {
    text.back() = '\0';
    text.pop_back();
  }
  wipe.keep = true;
  return text;
}

}  // namespace

std::string read_secret_file(const std::string& path, const char* what) { return read_file(path, what, true); }

std::string read_public_file(const std::string& path, const char* what) { return read_file(path, what, false); }

std::string read_token_file(const std::string& path) {
  std::string token = read_secret_file(path, "auth token");
  if (token.find_first_not_of(" \t\r\n\v\f") == std::string::npos) {
    OPENSSL_cleanse(token.data(), token.size());
    throw SecretFileError(
        "the auth token file '" + path +
        "' is empty or blank: a server with it would take calls without a token. Put a long random token in it: "
        "openssl rand -hex 32 > " +
        path + "; chmod 600 " + path + " (and give the same file to dtmfctl --token-file)");
  }
  return token;
}

ServerSecurity read_security_files(const std::string& tls_cert, const std::string& tls_key,
                                   const std::string& auth_token_file) {
  ServerSecurity security;
  if (!tls_cert.empty()) {
    security.tls_cert_pem = read_public_file(tls_cert, "TLS certificate");
    if (security.tls_cert_pem.empty()) throw SecretFileError("the TLS certificate file '" + tls_cert + "' is empty");
  }
  if (!tls_key.empty()) {
    security.tls_key_pem = read_secret_file(tls_key, "TLS key");
    if (security.tls_key_pem.empty()) throw SecretFileError("the TLS key file '" + tls_key + "' is empty");
  }
  if (!auth_token_file.empty()) security.auth_token = read_token_file(auth_token_file);
  return security;
}

}  // namespace dtmf::server
