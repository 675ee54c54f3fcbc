// A link key for tests, made from one byte: the same seed gives the same key, different
// seeds give different keys (a real key comes from security/key_file.h).
#pragma once

#include <array>
#include <memory>

#include "security/link_key.h"

namespace test_support {

inline std::shared_ptr<const dtmf::security::LinkKey> test_key(unsigned char seed) {
  std::array<unsigned char, dtmf::security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(seed ^ (29 * i));
  return dtmf::security::LinkKey::from_bytes(bytes);
}

}  // namespace test_support
