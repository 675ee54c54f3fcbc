// The air's fan-out: every AirEvent the sender publishes, copied to each watcher's own bounded
// queue. Publishing never waits for a watcher: a watcher whose queue is full loses its oldest
// entry, and the next entry it takes says how many it lost. Spectrum columns go to a short
// queue of their own, so that a slow watcher loses columns before it loses events, and each
// watcher gets them at its own rate and resolution (WatchOptions), taken from the full columns
// published (protocol/signal/spectrum_columns.h computes them only while someone watches).
//
//   publish(event) ──► [watcher 1 events | columns] ──take()──► WatchAir stream 1
//                  └─► [watcher 2 events | columns] ──take()──► WatchAir stream 2 ...
//
// A watcher is told its queue has something through the callback it set (on_ready), called
// after the fan-out's lock is let go, on the publisher's thread: it must not wait either (a
// gRPC reactor's StartWrite does not).
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "air_event.h"

namespace dtmf::server {

inline constexpr std::size_t kMaxWatchers = 16;
// The span of the spectrum's columns: every profile's bands, answers included (the seed's ACK
// chords at 1.5-4 kHz, commands up to 17 kHz); tests/server/watch_air_test.cpp checks that
// every profile's tones lie within.
inline constexpr double kSpectrumLowHz = 1000;
inline constexpr double kSpectrumHighHz = 20000;
inline constexpr double kMaxColumnsPerS = 50;  // the columns published while anyone watches the spectrum
inline constexpr double kDefaultColumnsPerS = 10;
inline constexpr int kMaxColumnBins = 512;  // the bins of a published column
inline constexpr int kDefaultColumnBins = 128;
// Each watcher's queues: a second of a busy air's events (a frame, its answer, their waits:
// a few dozen a second), and half a second of columns at the most.
inline constexpr std::size_t kWatchEvents = 1024;
inline constexpr std::size_t kWatchColumns = 25;

struct WatchOptions {
  std::string robot;  // empty: every robot
  bool spectrum = false;
  double columns_per_s = kDefaultColumnsPerS;  // 0 < … ≤ kMaxColumnsPerS
  int bins = kDefaultColumnBins;               // 1 ≤ … ≤ kMaxColumnBins
  std::size_t max_events = kWatchEvents;
  std::size_t max_columns = kWatchColumns;
};

// One entry a watcher takes, with what it lost since its last.
struct WatchEntry {
  AirEvent event;
  std::uint64_t dropped_events = 0;
  std::uint64_t dropped_columns = 0;
};

class AirFanout;

// One watcher's queues. Taken from by its own reader; filled by the fan-out.
class AirWatch {
 public:
  explicit AirWatch(WatchOptions options) : options_(std::move(options)) {}
  const WatchOptions& options() const { return options_; }

 private:
  friend class AirFanout;
  WatchOptions options_;
  // Guarded by the fan-out's lock.
  std::deque<AirEvent> events_;
  std::deque<AirEvent> columns_;
  std::uint64_t dropped_events_ = 0;
  std::uint64_t dropped_columns_ = 0;
  double next_column_ms_ = 0;  // audio time of the next column it takes
  std::function<void()> on_ready_;
};

class AirFanout {
 public:
  // A new watcher, or nothing when kMaxWatchers watch already or the fan-out is closed.
  // std::invalid_argument for options out of range (naming the field and its bounds).
  std::shared_ptr<AirWatch> watch(WatchOptions options);
  void unwatch(const std::shared_ptr<AirWatch>& watcher);
  // Called (never under the fan-out's lock) whenever `watcher`'s queue gains an entry or the
  // fan-out closes.
  void on_ready(const std::shared_ptr<AirWatch>& watcher, std::function<void()> ready);
  // Its oldest event, else its oldest column, with what it lost before; nothing when empty.
  std::optional<WatchEntry> take(AirWatch& watcher);
  // Whether the fan-out closed (the sender stops): nothing more will come.
  bool closed() const;

  void publish(AirEvent event);
  // A full column (kMaxColumnBins bins): each watcher of the spectrum takes it at its rate,
  // its bins merged to its resolution.
  void publish_column(double audio_ms, store::WallTime wall, const SpectrumColumn& column);
  // Whether anyone watches the spectrum (so that columns are worth computing).
  bool spectrum_watched() const { return spectrum_watchers_.load() > 0; }
  // Whether anyone watches at all (so that an event is worth making).
  bool watched() const { return watcher_count_.load() > 0; }
  std::size_t watchers() const;
  void close();

 private:
  // Calls the ready callbacks of `woken` (copied under the lock, called after it).
  static void wake(const std::vector<std::function<void()>>& woken);

  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<AirWatch>> watchers_;
  std::atomic<int> spectrum_watchers_{0};
  std::atomic<int> watcher_count_{0};
  bool closed_ = false;
};

// `column`'s bins merged, each of `bins` the loudest of the bins it covers.
SpectrumColumn merge_bins(const SpectrumColumn& column, int bins);

}  // namespace dtmf::server
