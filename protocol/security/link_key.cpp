#include "security/link_key.h"

#include "security/owned_file.h"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>

namespace dtmf::security {

namespace {

constexpr const char* kHeader = "# dtmf-teleop link key: keep it secret (docs/security.md)";
constexpr std::size_t kMaxFileBytes = 4096;

// A buffer in libsodium's guarded memory (locked out of swap), wiped and freed on every way out.
class GuardedBuffer {
 public:
  explicit GuardedBuffer(std::size_t size) {
    ensure_sodium();
    data_ = static_cast<char*>(sodium_malloc(size));
    if (data_ == nullptr) throw std::runtime_error("no guarded memory to read a key file (sodium_malloc failed)");
  }
  ~GuardedBuffer() { sodium_free(data_); }  // zeroes it first
  GuardedBuffer(const GuardedBuffer&) = delete;
  GuardedBuffer& operator=(const GuardedBuffer&) = delete;
  char* data() const { return data_; }

 private:
  char* data_;
};

constexpr const char* kBlanks = " \t\r";

std::string_view trim(std::string_view text) {
  const std::size_t first = text.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(kBlanks) - first + 1);
}

bool is_hex(char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

bool all_hex(std::string_view text) { return std::all_of(text.begin(), text.end(), is_hex); }

std::uint32_t hex_value(char c) {
  if (c >= '0' && c <= '9') return static_cast<std::uint32_t>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<std::uint32_t>(c - 'a' + 10);
  return static_cast<std::uint32_t>(c - 'A' + 10);
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

namespace {

// Reads the key file `name` into `text` (kMaxFileBytes + 1 bytes); its size. Opened first and
// checked on the open file, so that what is checked is what is read.
std::size_t read_key_file(const std::string& name, const GuardedBuffer& text) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) {
    throw KeyFileError("cannot read key file " + name + ": " + std::strerror(errno) +
                       " (make one with: dtmfctl keygen " + name + ")");
  }
  const FileDescriptor open_file(fd);
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw KeyFileError("cannot read key file " + name + ": " + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw KeyFileError("key file " + name + " is not a regular file");
  if ((info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw KeyFileError("key file " + name + " may be read or changed by others (mode " + octal_mode(info.st_mode) +
                       "); allow its owner only: chmod 600 " + name);
  }
  if (info.st_size > static_cast<off_t>(kMaxFileBytes)) throw KeyFileError("key file " + name + " is too long");
  std::size_t size = 0;
  while (size <= kMaxFileBytes) {
    const ssize_t got = ::read(fd, text.data() + size, kMaxFileBytes + 1 - size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw KeyFileError("cannot read key file " + name + ": " + std::strerror(errno));
    if (got == 0) break;
    size += static_cast<std::size_t>(got);
  }
  if (size > kMaxFileBytes) throw KeyFileError("key file " + name + " is too long");

  return size;
}

}  // namespace

std::shared_ptr<const LinkKey> LinkKey::load(const std::filesystem::path& file) {
  const std::string name = file.string();
  // The whole file in guarded memory, wiped on every way out; lines are read in place
  // (no stream buffers, no copies).
  const GuardedBuffer text(kMaxFileBytes + 1);
  const std::size_t size = read_key_file(name, text);

  std::shared_ptr<LinkKey> key(new LinkKey());
  bool have_key = false, have_id = false;
  std::uint32_t stated_id = 0;
  int number = 0;
  std::string_view rest(text.data(), size);
  while (!rest.empty()) {
    ++number;
    const std::size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    // Errors name the line and what it should be, never a byte of it: any of it may be the key.
    const auto refuse = [&](const std::string& what) {
      return KeyFileError("key file " + name + " line " + std::to_string(number) + ": " + what +
                          "; each line is 'key-id <8 hex digits>' or 'key <" + std::to_string(2 * kKeyBytes) +
                          " hex digits>', separated by a space (make a new file with dtmfctl keygen)");
    };
    const std::size_t gap = line.find_first_of(kBlanks);
    if (gap == std::string_view::npos) throw refuse("not a field and a value");
    const std::string_view field = line.substr(0, gap);
    const std::string_view value = trim(line.substr(gap));
    if (value.find_first_of(kBlanks) != std::string_view::npos) throw refuse("more than a field and a value");
    if (field == "key") {
      if (have_key) throw refuse("a second key line");
      std::size_t written = 0;
      if (value.size() != 2 * kKeyBytes || !all_hex(value) ||
          sodium_hex2bin(key->bytes_, kKeyBytes, value.data(), value.size(), nullptr, &written, nullptr) != 0 ||
          written != kKeyBytes) {
        throw refuse("the key is not " + std::to_string(2 * kKeyBytes) + " hexadecimal digits");
      }
      have_key = true;
    } else if (field == "key-id") {
      if (have_id) throw refuse("a second key-id line");
      if (value.size() != 8 || !all_hex(value)) throw refuse("the key id is not 8 hexadecimal digits");
      stated_id = 0;
      for (const char digit : value) stated_id = (stated_id << 4) | hex_value(digit);
      have_id = true;
    } else {
      throw refuse("neither a key-id nor a key line");
    }
  }
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
