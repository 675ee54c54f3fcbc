#include "signal/reread_queue.h"

#include <algorithm>

namespace dtmf::signal {

void RereadQueue::keep(int chords, long long end_sample, std::span<const HopCandidate> hypotheses) {
  if (delay_samples_ <= 0 || count_ == pending_.size()) return;
  PendingWindow& p = pending_[count_++];
  p.chords = chords;
  p.end_sample = end_sample;
  p.hypotheses = std::min(hypotheses.size(), p.grid.size());
  std::copy_n(hypotheses.begin(), p.hypotheses, p.grid.begin());
}

std::span<PendingWindow> RereadQueue::take_due(long long now, long long taken_at) {
  std::size_t kept = 0, due = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    const PendingWindow& p = pending_[i];
    if (taken_at >= p.end_sample) continue;
    if (now - p.end_sample < delay_samples_) {
      if (kept != i) pending_[kept] = p;
      ++kept;
    } else {
      due_[due++] = p;
    }
  }
  count_ = kept;
  return std::span(due_).first(due);
}

}  // namespace dtmf::signal
