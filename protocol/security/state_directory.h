// Security layer: the state directory the counter files live in (counter_file.h), opened
// once and trusted only when it is this user's and no one else may write in it, and a state
// file read from it as written there: never through a symbolic link, only a regular file,
// and no longer than any state.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace dtmf::security {

// Makes `directory` (mode 0700) when missing and opens it: the descriptor every counter file
// is then opened, made, renamed and removed relative to. Throws std::runtime_error naming
// what is wrong (another user's, others may write in it, not writable) and the fix.
int open_state_directory(const std::filesystem::path& directory);

// The file `name` in the directory, or nothing when there is none. Throws
// counter_text::Damage for a link, a file that is not regular, or one longer than any state;
// std::runtime_error when it cannot be read.
std::optional<std::string> read_state(int directory_fd, const std::filesystem::path& path, const std::string& name);

}  // namespace dtmf::security
