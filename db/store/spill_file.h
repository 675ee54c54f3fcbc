// Store library: where rows wait while the database is away.
//
// Rows are appended as JSON lines to `path`. To replay, the file is first renamed to
// `path.replaying` (new rows then start a fresh file), read in order, and removed once all
// of it is in the database. Files left by a program that stopped or crashed are replayed
// by the next one. Rows the database refuses for good go to `path.rejected` for a person
// to look at. Every method is thread-safe.
#pragma once

#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

namespace dtmf::store {

class SpillFile {
 public:
  explicit SpillFile(std::string path);
  ~SpillFile();

  // Appends lines (each one row, no newline). Throws std::runtime_error if the disk refuses.
  void append(const std::vector<std::string>& lines);
  void append(const std::string& line);
  void reject(const std::string& line, const std::string& reason);

  // True if rows wait in the file or in a replay under way.
  bool pending() const;
  // The next `max_lines` rows to replay, oldest first (empty when there are none).
  std::vector<std::string> next_replay_chunk(std::size_t max_lines);
  // The last chunk is in the database: forget it (and the replay file once it is used up).
  void replay_chunk_done();
  // The last chunk could not be written: offer it again next time.
  void replay_chunk_failed();

  const std::string& path() const { return path_; }
  std::size_t lines_appended() const;

 private:
  void open_for_append();

  std::string path_;
  std::string replay_path_;
  mutable std::mutex mutex_;
  std::FILE* out_ = nullptr;
  std::size_t appended_ = 0;
  bool active_has_rows_ = false;
  // Replay state (the worker's).
  std::ifstream replay_;
  std::streampos chunk_start_{};
  bool replay_exhausted_ = false;
};

}  // namespace dtmf::store
