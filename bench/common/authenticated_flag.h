// --authenticated: a frame benchmark runs the profile's authenticated frames (a MAC and a
// freshness counter; with the fast profile, 80 bits on three chords) under a fixed key, so
// that a run is repeated exactly (another key changes the MACs' and tags' values, not how
// often they are heard).
// Header-only.
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <memory>

#include "security/link_key.h"

namespace dtmf::bench {

inline void add_authenticated_flag(CLI::App& app, bool& authenticated) {
  app.add_flag("--authenticated", authenticated,
               "authenticated frames (a MAC and a freshness counter) under a fixed key");
}

inline std::shared_ptr<const security::LinkKey> bench_key(bool authenticated) {
  if (!authenticated) return nullptr;
  std::array<unsigned char, security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(0xb5 ^ (31 * i));
  return security::LinkKey::from_bytes(bytes);
}

}  // namespace dtmf::bench
