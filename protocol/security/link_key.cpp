#include "security/link_key.h"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace dtmf::security {

namespace {

constexpr const char* kHeader = "# dtmf-teleop link key: keep it secret (docs/security.md)";
constexpr std::size_t kMaxFileBytes = 4096;

std::string octal_mode(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

std::uint32_t derive_id(const unsigned char* key) {
  static constexpr char kLabel[] = "dtmf-teleop key id";
  std::array<unsigned char, 16> out{};
  crypto_generichash(out.data(), out.size(), reinterpret_cast<const unsigned char*>(kLabel), sizeof kLabel - 1, key,
                     kKeyBytes);
  return (std::uint32_t{out[0]} << 24) | (std::uint32_t{out[1]} << 16) | (std::uint32_t{out[2]} << 8) | out[3];
}

}  // namespace

void ensure_sodium() {
  static const int status = sodium_init();
  if (status < 0) throw std::runtime_error("libsodium could not start (sodium_init failed)");
}

LinkKey::LinkKey() {
  ensure_sodium();
  bytes_ = static_cast<unsigned char*>(sodium_malloc(kKeyBytes));
  if (bytes_ == nullptr) throw std::runtime_error("no guarded memory for a key (sodium_malloc failed)");
}

LinkKey::~LinkKey() { sodium_free(bytes_); }

std::span<const unsigned char, kKeyBytes> LinkKey::bytes() const {
  return std::span<const unsigned char, kKeyBytes>(bytes_, kKeyBytes);
}

std::string LinkKey::id_hex() const {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", id_);
  return text;
}

std::shared_ptr<const LinkKey> LinkKey::generate() {
  std::shared_ptr<LinkKey> key(new LinkKey());
  randombytes_buf(key->bytes_, kKeyBytes);
  key->id_ = derive_id(key->bytes_);
  return key;
}

std::shared_ptr<const LinkKey> LinkKey::from_bytes(std::span<const unsigned char, kKeyBytes> bytes) {
  std::shared_ptr<LinkKey> key(new LinkKey());
  std::copy(bytes.begin(), bytes.end(), key->bytes_);
  key->id_ = derive_id(key->bytes_);
  return key;
}

std::shared_ptr<const LinkKey> LinkKey::load(const std::filesystem::path& file) {
  const std::string name = file.string();
  struct stat info {};
  if (::stat(name.c_str(), &info) != 0) {
    throw KeyFileError("cannot read key file " + name + ": " + std::strerror(errno) +
                       " (make one with: dtmfctl keygen " + name + ")");
  }
  if (!S_ISREG(info.st_mode)) throw KeyFileError("key file " + name + " is not a regular file");
  if ((info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw KeyFileError("key file " + name + " may be read or changed by others (mode " + octal_mode(info.st_mode) +
                       "); allow its owner only: chmod 600 " + name);
  }
  if (info.st_size > static_cast<off_t>(kMaxFileBytes)) throw KeyFileError("key file " + name + " is too long");
  std::ifstream in(file);
  if (!in) throw KeyFileError("cannot open key file " + name + ": " + std::strerror(errno));

  std::shared_ptr<LinkKey> key(new LinkKey());
  bool have_key = false, have_id = false;
  std::uint32_t stated_id = 0;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string field, value;
    words >> field >> value;
    // Errors name the line and the field, never the value: it may be the key.
    const std::string where = "key file " + name + " line " + std::to_string(number);
    if (field == "key") {
      std::size_t written = 0;
      if (value.size() != 2 * kKeyBytes ||
          sodium_hex2bin(key->bytes_, kKeyBytes, value.data(), value.size(), nullptr, &written, nullptr) != 0 ||
          written != kKeyBytes) {
        sodium_memzero(value.data(), value.size());
        throw KeyFileError(where + ": the key must be " + std::to_string(2 * kKeyBytes) +
                           " hexadecimal digits (make a new one with dtmfctl keygen)");
      }
      sodium_memzero(value.data(), value.size());
      have_key = true;
    } else if (field == "key-id") {
      char* end = nullptr;
      const unsigned long id = std::strtoul(value.c_str(), &end, 16);
      if (value.size() != 8 || end != value.c_str() + value.size()) {
        throw KeyFileError(where + ": the key id must be 8 hexadecimal digits");
      }
      stated_id = static_cast<std::uint32_t>(id);
      have_id = true;
    } else {
      throw KeyFileError(where + ": unknown field '" + field.substr(0, 20) + "' (expected key-id or key)");
    }
  }
  sodium_memzero(line.data(), line.size());
  if (!have_key || !have_id)
    throw KeyFileError("key file " + name + " lacks its " + (have_key ? "key-id" : "key") + " line");
  key->id_ = derive_id(key->bytes_);
  if (key->id_ != stated_id) {
    throw KeyFileError("key file " + name +
                       ": its key id does not match its key (the file is damaged or was edited); " +
                       "copy it again from the machine that made it");
  }
  return key;
}

void LinkKey::save(const std::filesystem::path& file) const {
  const std::string name = file.string();
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw KeyFileError("cannot create key file " + name + ": " + std::strerror(errno) +
                       (errno == EEXIST ? " (a key is never overwritten: remove the old file first)" : ""));
  }
  std::array<char, 2 * kKeyBytes + 1> hex{};
  sodium_bin2hex(hex.data(), hex.size(), bytes_, kKeyBytes);
  std::string text = std::string(kHeader) + "\nkey-id " + id_hex() + "\nkey " + std::string(hex.data()) + "\n";
  sodium_memzero(hex.data(), hex.size());
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  sodium_memzero(text.data(), text.size());
  if (!ok) {
    ::unlink(name.c_str());
    throw KeyFileError("cannot write key file " + name + ": " + std::strerror(error));
  }
}

}  // namespace dtmf::security
