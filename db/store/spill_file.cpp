#include "spill_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace dtmf::store {

namespace fs = std::filesystem;

SpillFile::SpillFile(std::string path) : path_(std::move(path)), replay_path_(path_ + ".replaying") {
  const fs::path parent = fs::path(path_).parent_path();
  std::error_code ignored;
  // A directory made here is this user's alone (0700, whatever the umask): it holds the log's
  // rows, and as a user's default state directory also the key's counters, which refuse a
  // directory others may write (security/counter_file.h).
  if (!parent.empty() && fs::create_directories(parent, ignored))
    fs::permissions(parent, fs::perms::owner_all, fs::perm_options::replace, ignored);
  active_has_rows_ = fs::exists(path_) && fs::file_size(path_) > 0;
}

SpillFile::~SpillFile() {
  if (out_) std::fclose(out_);
}

void SpillFile::open_for_append() {
  if (out_) return;
  out_ = std::fopen(path_.c_str(), "a");
  if (!out_) {
    throw std::runtime_error("cannot write the spill file '" + path_ + "': " + std::strerror(errno) +
                             " (set --spill-file to a writable place)");
  }
}

void SpillFile::append(const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  std::lock_guard lock(mutex_);
  open_for_append();
  for (const std::string& line : lines) {
    std::fwrite(line.data(), 1, line.size(), out_);
    std::fputc('\n', out_);
  }
  if (std::fflush(out_) != 0) {
    throw std::runtime_error("writing the spill file '" + path_ + "' failed: " + std::strerror(errno));
  }
  appended_ += lines.size();
  active_has_rows_ = true;
}

void SpillFile::append(const std::string& line) { append(std::vector<std::string>{line}); }

void SpillFile::reject(const std::string& line, const std::string& reason) {
  std::lock_guard lock(mutex_);
  if (std::FILE* f = std::fopen((path_ + ".rejected").c_str(), "a")) {
    std::fprintf(f, "# %s\n%s\n", reason.c_str(), line.c_str());
    std::fclose(f);
  }
}

bool SpillFile::pending() const {
  std::lock_guard lock(mutex_);
  return active_has_rows_ || replay_.is_open() || fs::exists(replay_path_);
}

std::size_t SpillFile::lines_appended() const {
  std::lock_guard lock(mutex_);
  return appended_;
}

std::vector<std::string> SpillFile::next_replay_chunk(std::size_t max_lines) {
  std::lock_guard lock(mutex_);
  if (!replay_.is_open()) {
    // Start a replay: take over the file of waiting rows, unless an earlier replay remains.
    if (!fs::exists(replay_path_)) {
      if (!active_has_rows_) return {};
      if (out_) {
        std::fclose(out_);
        out_ = nullptr;
      }
      fs::rename(path_, replay_path_);
      active_has_rows_ = false;
    }
    replay_.open(replay_path_);
    replay_exhausted_ = false;
  }
  chunk_start_ = replay_.tellg();
  std::vector<std::string> lines;
  std::string line;
  while (lines.size() < max_lines && std::getline(replay_, line)) {
    if (!line.empty()) lines.push_back(std::move(line));
  }
  if (lines.size() < max_lines) replay_exhausted_ = true;
  return lines;
}

void SpillFile::replay_chunk_done() {
  std::lock_guard lock(mutex_);
  if (replay_exhausted_ && replay_.is_open()) {
    replay_.close();
    fs::remove(replay_path_);
  }
}

void SpillFile::replay_chunk_failed() {
  std::lock_guard lock(mutex_);
  replay_.clear();
  replay_.seekg(chunk_start_);
  replay_exhausted_ = false;
}

}  // namespace dtmf::store
