// What waits to go to one page, bounded. The gRPC side puts (never waiting); the page's writer
// takes, waiting. A page that reads too slowly loses spectrum columns first, oldest first, and
// is told how many in the next message; if even its events and replies fill the box, it is
// closed (it reconnects, and shows it), rather than the console holding more for it.
// Pure logic and a condition variable; no I/O.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace dtmf::console {

class PageOutbox {
 public:
  // 2 MB: about 8 s of full-resolution columns at 50 a second, or 10 000 events.
  static constexpr std::size_t kMaxBytes = 2 * 1024 * 1024;

  explicit PageOutbox(std::size_t max_bytes = kMaxBytes) : max_bytes_(max_bytes) {}

  // Queues `text`; drops the oldest droppable entries while over the bound. False once the
  // box overflowed with what may not be dropped (or was shut): the page is to be closed.
  bool put(std::string text, bool droppable);
  // The next text, waiting for one; nothing once shut. A text that follows dropped columns
  // is preceded by {"dropped_columns":N}.
  std::optional<std::string> take();
  void shut();

  std::uint64_t dropped_columns() const;
  // Whether what may not be dropped filled it (the page is to be closed).
  bool overflowed() const;

 private:
  struct Entry {
    std::string text;
    bool droppable;
  };
  const std::size_t max_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Entry> entries_;
  std::size_t bytes_ = 0;
  std::uint64_t unreported_drops_ = 0;
  std::uint64_t dropped_columns_ = 0;
  bool shut_ = false;
  bool overflowed_ = false;
};

}  // namespace dtmf::console
