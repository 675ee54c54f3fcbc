// A user's own directory for dtmf-teleop under an XDG base directory (the XDG Base Directory
// Specification): $VARIABLE/dtmf-teleop, else ~/HOME_RELATIVE/dtmf-teleop; nothing when
// neither variable is set (a service without a home). Header-only, no dependencies: the
// programs' flags and the store's spill file both use it.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace dtmf::program {

inline std::optional<std::string> xdg_user_dir(const char* variable, const char* home_relative) {
  if (const char* base = std::getenv(variable); base && *base) return std::string(base) + "/dtmf-teleop";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/" + home_relative + "/dtmf-teleop";
  return std::nullopt;
}

// $XDG_STATE_HOME/dtmf-teleop, else ~/.local/state/dtmf-teleop.
inline std::optional<std::string> user_state_dir() { return xdg_user_dir("XDG_STATE_HOME", ".local/state"); }

}  // namespace dtmf::program
