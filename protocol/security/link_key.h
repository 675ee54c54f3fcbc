// Security layer: the key one sender shares with its robots, and the file that holds it.
//
// A key is 32 random bytes from libsodium (randombytes_buf) and a 32-bit key id derived from
// it (keyed BLAKE2b of a fixed label), so logs, state files and every MAC input can name the
// key without revealing it. The bytes live in libsodium's guarded memory (sodium_malloc:
// locked out of swap, wiped when freed) and are read only by frame_mac.cpp.
//
// The file is three lines of text, written by `dtmfctl keygen` with mode 0600:
//   # dtmf-teleop link key: keep it secret (docs/security.md)
//   key-id 1a2b3c4d
//   key 4f1b...   (64 hexadecimal digits)
// A file that its group or others may read or write is refused before it is read, with the
// chmod that fixes it; a key id that does not match the key (a damaged or hand-edited file)
// is refused too. No error text ever carries the file's content.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

namespace dtmf::security {

inline constexpr std::size_t kKeyBytes = 32;

class KeyFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LinkKey {
 public:
  // A new random key.
  static std::shared_ptr<const LinkKey> generate();
  // A key of the given bytes (tests and benchmarks that must be repeatable).
  static std::shared_ptr<const LinkKey> from_bytes(std::span<const unsigned char, kKeyBytes> bytes);
  // The key in `file`; throws KeyFileError saying what is wrong and how to fix it.
  static std::shared_ptr<const LinkKey> load(const std::filesystem::path& file);

  ~LinkKey();
  LinkKey(const LinkKey&) = delete;
  LinkKey& operator=(const LinkKey&) = delete;

  // Writes the key to a new file with mode 0600; refuses to overwrite an existing one.
  void save(const std::filesystem::path& file) const;

  std::uint32_t id() const { return id_; }
  std::string id_hex() const;  // "1a2b3c4d"
  std::span<const unsigned char, kKeyBytes> bytes() const;

 private:
  LinkKey();
  unsigned char* bytes_;  // sodium_malloc'd
  std::uint32_t id_ = 0;
};

// libsodium's sodium_init(), once; throws if the library cannot start.
void ensure_sodium();

}  // namespace dtmf::security
