// Signal layer: the fast listener's windows waiting for a second look (one job of
// hop_listener.h). A window none of whose hypotheses was taken, or one a band short of the
// gate, waits `reread_delay_hops` windows: a window a hop early fails where the next one
// decodes, and a frame taken in or after it (its own, or one that holds the windows after it)
// drops it. Windows come in time order, so those due form the queue's front. Pure: times are
// sample counts the listener passes in; allocation-free.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "signal/hop_candidate.h"

namespace dtmf::signal {

struct PendingWindow {
  int chords = 2;
  long long end_sample = 0;  // its window's end
  std::size_t hypotheses = 0;
  std::array<HopCandidate, kOffsetHypotheses> grid{};  // the grid's readings, as offered
};

class RereadQueue {
 public:
  // Two frame shapes a window, for the newest window and those of the delay.
  static constexpr std::size_t kCapacity = 8;

  // delay_samples <= 0: no second looks (keep() keeps nothing).
  explicit RereadQueue(long long delay_samples) : delay_samples_(delay_samples) {}

  // Keeps a window that ended at `end_sample` with its grid hypotheses (none for a window
  // short of the gate); nothing when second looks are off or the queue is full.
  void keep(int chords, long long end_sample, std::span<const HopCandidate> hypotheses);
  // The windows whose delay has passed at `now` with no frame taken in or after them
  // (`taken_at`: the end of the latest window a frame was taken in, or -1); they leave the
  // queue, and so do those a frame was taken in or after. Valid until the next call.
  std::span<PendingWindow> take_due(long long now, long long taken_at);
  // Drops every window (a frame was taken now: it holds them all).
  void clear() { count_ = 0; }
  bool empty() const { return count_ == 0; }

 private:
  long long delay_samples_;
  std::array<PendingWindow, kCapacity> pending_{};
  std::size_t count_ = 0;
  std::array<PendingWindow, kCapacity> due_{};
};

}  // namespace dtmf::signal
