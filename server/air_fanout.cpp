#include "air_fanout.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::server {

namespace {

void check_options(const WatchOptions& o) {
  if (o.spectrum && !(o.columns_per_s > 0 && o.columns_per_s <= kMaxColumnsPerS))
    throw std::invalid_argument("columns_per_s " + std::to_string(o.columns_per_s) +
                                " is out of range: give 0 (10 columns a second) up to " +
                                std::to_string(static_cast<int>(kMaxColumnsPerS)));
  if (o.spectrum && !(o.bins >= 1 && o.bins <= kMaxColumnBins))
    throw std::invalid_argument("bins " + std::to_string(o.bins) + " is out of range: give 0 (" +
                                std::to_string(kDefaultColumnBins) + " bins) up to " + std::to_string(kMaxColumnBins));
  if (o.max_events == 0 || o.max_columns == 0) throw std::invalid_argument("a watcher's queues need room");
}

// Pushes `event` onto `queue`, dropping its oldest past `capacity`; counts the drop.
void push_bounded(std::deque<AirEvent>& queue, AirEvent event, std::size_t capacity, std::uint64_t& dropped) {
  if (queue.size() >= capacity) {
    queue.pop_front();
    ++dropped;
  }
  queue.push_back(std::move(event));
}

}  // namespace

SpectrumColumn merge_bins(const SpectrumColumn& column, int bins) {
  const int given = static_cast<int>(column.level_dbfs.size());
  if (bins >= given) return column;
  SpectrumColumn merged{column.low_hz, column.step_hz * given / bins, column.window_ms, {}};
  merged.level_dbfs.resize(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) {
    const int from = b * given / bins;
    const int to = std::max(from + 1, (b + 1) * given / bins);
    merged.level_dbfs[static_cast<std::size_t>(b)] =
        *std::max_element(column.level_dbfs.begin() + from, column.level_dbfs.begin() + to);
  }
  return merged;
}

std::shared_ptr<AirWatch> AirFanout::watch(WatchOptions options) {
  check_options(options);
  auto watcher = std::make_shared<AirWatch>(std::move(options));
  std::lock_guard lock(mutex_);
  if (closed_ || watchers_.size() >= kMaxWatchers) return nullptr;
  watchers_.push_back(watcher);
  ++watcher_count_;
  if (watcher->options().spectrum) ++spectrum_watchers_;
  return watcher;
}

void AirFanout::unwatch(const std::shared_ptr<AirWatch>& watcher) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(watchers_.begin(), watchers_.end(), watcher);
  if (it == watchers_.end()) return;
  --watcher_count_;
  if (watcher->options().spectrum) --spectrum_watchers_;
  watchers_.erase(it);
  watcher->on_ready_ = nullptr;
}

void AirFanout::on_ready(const std::shared_ptr<AirWatch>& watcher, std::function<void()> ready) {
  std::lock_guard lock(mutex_);
  watcher->on_ready_ = std::move(ready);
}

std::optional<WatchEntry> AirFanout::take(AirWatch& watcher) {
  std::lock_guard lock(mutex_);
  std::deque<AirEvent>& from = !watcher.events_.empty() ? watcher.events_ : watcher.columns_;
  if (from.empty()) return std::nullopt;
  WatchEntry entry{std::move(from.front()), std::exchange(watcher.dropped_events_, 0),
                   std::exchange(watcher.dropped_columns_, 0)};
  from.pop_front();
  return entry;
}

bool AirFanout::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

std::size_t AirFanout::watchers() const {
  std::lock_guard lock(mutex_);
  return watchers_.size();
}

void AirFanout::publish(AirEvent event) {
  std::vector<std::function<void()>> woken;
  {
    std::lock_guard lock(mutex_);
    for (const auto& w : watchers_) {
      if (!concerns(event, w->options_.robot)) continue;
      push_bounded(w->events_, event, w->options_.max_events, w->dropped_events_);
      if (w->on_ready_) woken.push_back(w->on_ready_);
    }
  }
  wake(woken);
}

void AirFanout::publish_column(double audio_ms, store::WallTime wall, const SpectrumColumn& column) {
  std::vector<std::function<void()>> woken;
  {
    std::lock_guard lock(mutex_);
    for (const auto& w : watchers_) {
      if (!w->options_.spectrum || audio_ms < w->next_column_ms_) continue;
      // Due again a period after this one was due, not after it came, so that the rate holds
      // on average; a watcher that began late starts from now.
      const double period_ms = 1000.0 / w->options_.columns_per_s;
      const double next_ms = w->next_column_ms_ + period_ms;
      w->next_column_ms_ = next_ms > audio_ms ? next_ms : audio_ms + period_ms;
      push_bounded(w->columns_, AirEvent{audio_ms, wall, merge_bins(column, w->options_.bins)}, w->options_.max_columns,
                   w->dropped_columns_);
      if (w->on_ready_) woken.push_back(w->on_ready_);
    }
  }
  wake(woken);
}

void AirFanout::close() {
  std::vector<std::function<void()>> woken;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    for (const auto& w : watchers_)
      if (w->on_ready_) woken.push_back(w->on_ready_);
  }
  wake(woken);
}

void AirFanout::wake(const std::vector<std::function<void()>>& woken) {
  for (const auto& ready : woken) ready();
}

}  // namespace dtmf::server
