#include "page_outbox.h"

#include <algorithm>

namespace dtmf::console {

bool PageOutbox::put(std::string text, bool droppable) {
  {
    std::lock_guard lock(mutex_);
    if (shut_ || overflowed_) return false;
    bytes_ += text.size();
    entries_.push_back({std::move(text), droppable});
    while (bytes_ > max_bytes_) {
      const auto oldest = std::find_if(entries_.begin(), entries_.end(), [](const Entry& e) { return e.droppable; });
      if (oldest == entries_.end()) {
        overflowed_ = true;  // what is left may not be lost: the page goes
        break;
      }
      bytes_ -= oldest->text.size();
      entries_.erase(oldest);
      ++unreported_drops_;
      ++dropped_columns_;
    }
  }
  ready_.notify_one();
  std::lock_guard lock(mutex_);
  return !overflowed_;
}

std::optional<std::string> PageOutbox::take() {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, [this] { return shut_ || overflowed_ || !entries_.empty(); });
  if (shut_ || overflowed_) return std::nullopt;
  if (unreported_drops_ > 0) {
    std::string note = "{\"dropped_columns\":" + std::to_string(unreported_drops_) + "}";
    unreported_drops_ = 0;
    return note;
  }
  Entry entry = std::move(entries_.front());
  entries_.pop_front();
  bytes_ -= entry.text.size();
  return std::move(entry.text);
}

void PageOutbox::shut() {
  {
    std::lock_guard lock(mutex_);
    shut_ = true;
  }
  ready_.notify_all();
}

std::uint64_t PageOutbox::dropped_columns() const {
  std::lock_guard lock(mutex_);
  return dropped_columns_;
}

bool PageOutbox::overflowed() const {
  std::lock_guard lock(mutex_);
  return overflowed_;
}

}  // namespace dtmf::console
