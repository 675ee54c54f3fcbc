#include "signal/debouncer.h"

#include <algorithm>
#include <cmath>

#include "units/decibels.h"

namespace dtmf::signal {

Debouncer::Debouncer(const DebounceParams& params)
    : params_(params), rearm_ratio_(units::amplitude_ratio_from_db(-params.rearm_drop_db)) {}

void Debouncer::reset() {
  size_ = 0;
  head_ = 0;
  locked_symbol_.reset();
  rearmed_ = true;
  sounded_ms_ = 0;
  last_window_ms_ = 0;
  locked_sounded_ = false;
}

bool Debouncer::locked_out(const Detection& detection, double t_ms) {
  if (!locked_symbol_ || *locked_symbol_ != detection.symbol) return false;
  if (!rearmed_) {
    // A new occurrence shows as a dip of rearm_drop_db below the peak, then a rise of as
    // much again; a fading tail only dips, and a chord's own onset only rises.
    const bool dipped = locked_dip_level_ <= locked_peak_level_ * rearm_ratio_;
    if (dipped && detection.level * rearm_ratio_ >= locked_dip_level_) {
      rearmed_ = true;
    } else if (detection.level > locked_peak_level_) {
      locked_peak_level_ = locked_dip_level_ = detection.level;
    } else {
      locked_dip_level_ = std::min(locked_dip_level_, detection.level);
    }
  }
  return t_ms < locked_until_ms_ || !rearmed_;
}

bool Debouncer::still_sounding_once(double t_ms) const {
  return params_.symbol_ms > 0 && t_ms < locked_first_ms_ + params_.symbol_ms + params_.max_dropout_ms &&
         sounded_ms_ < params_.symbol_ms + params_.presence_margin_ms;
}

std::optional<Debouncer::Pass> Debouncer::on_window(double t_ms, std::optional<Detection> detection) {
  const double hop_ms = t_ms - last_window_ms_;
  last_window_ms_ = t_ms;
  const bool locked_sounds =
      detection && locked_symbol_ == detection->symbol && detection->level >= locked_peak_level_ * rearm_ratio_;
  if (locked_sounds) {
    sounded_ms_ += hop_ms;
    if (!locked_sounded_) locked_onset_ms_ = t_ms;
  }
  locked_sounded_ = locked_sounds;
  if (!detection) {
    rearmed_ = true;
    return std::nullopt;
  }
  // A copy of the symbol that just passed, rearm_drop_db or more below its peak, is its
  // reverberant tail: it neither counts nor re-arms (a chord's last, ragged window often
  // detects nothing, and re-arming there let the tail pass again once the lockout ended).
  if (locked_symbol_ == detection->symbol && t_ms < locked_until_ms_ + params_.lockout_ms &&
      detection->level < locked_peak_level_ * rearm_ratio_) {
    if (!rearmed_) locked_dip_level_ = std::min(locked_dip_level_, detection->level);
    return std::nullopt;
  }
  if (locked_symbol_ && *locked_symbol_ != detection->symbol) rearmed_ = true;
  if (locked_out(*detection, t_ms)) return std::nullopt;

  // Forget detections that fell out of the window (or would overflow the ring).
  while (size_ > 0 && (t_ms - recent_[head_].t_ms > params_.window_ms || size_ == kCapacity)) {
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  recent_[(head_ + size_) % kCapacity] = Counted{detection->symbol, t_ms};
  ++size_;

  int count = 0;
  double first_ms = t_ms;
  for (std::size_t i = 0; i < size_; ++i) {
    const Counted& c = recent_[(head_ + i) % kCapacity];
    if (c.symbol != detection->symbol) continue;
    if (count == 0) first_ms = c.t_ms;
    ++count;
  }
  if (count < params_.min_detections) return std::nullopt;
  if (locked_symbol_ == detection->symbol) {
    if (still_sounding_once(t_ms)) return std::nullopt;
    // Held a while, its first detections left the window: it started at its own onset.
    if (params_.symbol_ms > 0) first_ms = std::min(first_ms, locked_onset_ms_);
  }

  // Drop this symbol's detections so that they cannot count again after the lockout.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < size_; ++i) {
    const Counted c = recent_[(head_ + i) % kCapacity];
    if (c.symbol != detection->symbol) recent_[(head_ + kept++) % kCapacity] = c;
  }
  size_ = kept;
  locked_symbol_ = detection->symbol;
  locked_until_ms_ = t_ms + params_.lockout_ms;
  locked_peak_level_ = locked_dip_level_ = detection->level;
  rearmed_ = false;
  locked_first_ms_ = locked_onset_ms_ = first_ms;
  locked_sounded_ = true;
  sounded_ms_ = t_ms - first_ms + hop_ms;  // the windows that passed it, the first one's hop included
  return Pass{detection->symbol, first_ms, t_ms};
}

}  // namespace dtmf::signal
