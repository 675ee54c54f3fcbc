#include "signal/debouncer.h"

namespace dtmf::signal {

Debouncer::Debouncer(const DebounceParams& params) : params_(params) {}

void Debouncer::reset() {
  size_ = 0;
  head_ = 0;
  locked_symbol_.reset();
}

std::optional<Debouncer::Pass> Debouncer::on_detection(std::uint32_t symbol, double t_ms) {
  if (locked_symbol_ && *locked_symbol_ == symbol && t_ms < locked_until_ms_) return std::nullopt;

  // Forget detections that fell out of the window (or would overflow the ring).
  while (size_ > 0 && (t_ms - recent_[head_].t_ms > params_.window_ms || size_ == kCapacity)) {
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  recent_[(head_ + size_) % kCapacity] = Detection{symbol, t_ms};
  ++size_;

  int count = 0;
  double first_ms = t_ms;
  for (std::size_t i = 0; i < size_; ++i) {
    const Detection& d = recent_[(head_ + i) % kCapacity];
    if (d.symbol != symbol) continue;
    if (count == 0) first_ms = d.t_ms;
    ++count;
  }
  if (count < params_.min_detections) return std::nullopt;

  // Drop this symbol's detections so that they cannot count again after the lockout.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < size_; ++i) {
    const Detection d = recent_[(head_ + i) % kCapacity];
    if (d.symbol != symbol) recent_[(head_ + kept++) % kCapacity] = d;
  }
  size_ = kept;
  locked_symbol_ = symbol;
  locked_until_ms_ = t_ms + params_.lockout_ms;
  return Pass{symbol, first_ms, t_ms};
}

}  // namespace dtmf::signal
