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
#include <filesystem>

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

// What a file must be before a byte of it is read.
struct Demands {
  bool secret = false;                   // only its owner may read or write it
  const TrustedFile* trusted = nullptr;  // this user's or root's, and only its owner may write it
};

// Why the open file `info` (`path`, named `file` in errors) must not be read, or "".
std::string refusal_of(const struct stat& info, const std::string& file, const std::string& path, Demands demands) {
  // A pipe (--auth-token-file <(...)) is fine for a secret; a directory or a device is not what
  // was meant, and a trusted file must stay what was checked.
  if (!S_ISREG(info.st_mode) && (demands.trusted || !S_ISFIFO(info.st_mode))) return file + " is not a regular file";
  if (demands.secret && (info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    return file + " may be read or changed by others (mode " + octal_mode(info.st_mode) +
           "); allow its owner only: chmod 600 " + path;
  }
  if (!demands.trusted) return "";
  const std::string user = std::to_string(::geteuid());
  if (info.st_uid != ::geteuid() && info.st_uid != 0) {
    return file + " belongs to user " + std::to_string(info.st_uid) + ", neither this one (" + user +
           ") nor root, and it decides " + demands.trusted->decides + "; make it this user's: chown " + user + " " +
           path;
  }
  if ((info.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    return file + " may be changed by others (mode " + octal_mode(info.st_mode) + "), and it decides " +
           demands.trusted->decides + "; allow its owner only to write it: chmod go-w " + path;
  }
  return "";
}

// A trusted file's path that is a symbolic link: what to name instead.
std::string link_refusal(const std::string& file, const std::string& path, const TrustedFile& kind) {
  std::error_code error;
  const std::filesystem::path target = std::filesystem::weakly_canonical(path, error);
  const std::string fix = error ? std::string(kind.flag) + " \"$(readlink -f " + path + ")\""
                                : std::string(kind.flag) + " " + target.string();
  return file + " is a symbolic link" + (error ? "" : " (to " + target.string() + ")") +
         ": whoever may change the link chooses the file, which decides " + kind.decides +
         ". Name the file itself: " + fix;
}

// Reads `path` after checking the open file against `demands` (refusal_of), so that what is
// checked is what is read. Errors name the file, never its content.
std::string read_file(const std::string& path, const char* what, Demands demands) {
  const std::string file = std::string("the ") + what + " file '" + path + "'";
  // A trusted file is never reached through a link, and a FIFO planted in its place does not
  // hold the open until a writer comes.
  const int flags = O_RDONLY | O_CLOEXEC | O_NOCTTY | (demands.trusted ? O_NOFOLLOW | O_NONBLOCK : 0);
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0 && errno == ELOOP && demands.trusted) throw SecretFileError(link_refusal(file, path, *demands.trusted));
  if (fd < 0) throw SecretFileError("cannot read " + file + ": " + std::strerror(errno));
  const FileDescriptor open_file(fd);
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw SecretFileError("cannot read " + file + ": " + std::strerror(errno));
  if (const std::string refusal = refusal_of(info, file, path, demands); !refusal.empty())
    throw SecretFileError(refusal);
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

std::string read_secret_file(const std::string& path, const char* what) {
  return read_file(path, what, {.secret = true});
}

std::string read_public_file(const std::string& path, const char* what) { return read_file(path, what, {}); }

std::string read_trusted_file(const std::string& path, const TrustedFile& kind) {
  return read_file(path, kind.what, {.trusted = &kind});
}

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
