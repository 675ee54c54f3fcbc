#include "reliability/air_access.h"

#include <algorithm>

namespace dtmf::reliability {

namespace {
// A yielding sender's quiet: the others' quiet hold and their longest backoff, and two slots
// more, so that a sender that waited has started, and is heard, before we listen again.
double yield_window_ms(double quiet_ms) { return quiet_ms + (kBackoffSlots + 2) * kSlotMs; }
}  // namespace

bool AirAccess::shared(const CarrierSense& sense, double now_ms) const {
  return sense.last_busy_ms() && now_ms - *sense.last_busy_ms() < kSharedMemoryMs;
}

double AirAccess::draw_backoff_ms(int slots) {
  std::uniform_int_distribution<int> slot(0, slots - 1);
  return slot(random_) * kSlotMs;
}

std::optional<double> AirAccess::pause_left_ms(const CarrierSense& sense, double now_ms, bool shared) {
  const std::optional<double> own_end_ms = sense.own_ended_ms();
  if (!run_start_ms_ || !own_end_ms) return std::nullopt;
  if (*own_end_ms - *run_start_ms_ < (shared ? kMaxHoldMs : kListenEveryMs)) return std::nullopt;
  const double window_ms = shared ? yield_window_ms(quiet_ms_) : kListenWindowMs;
  const std::optional<double> quiet_since = sense.quiet_since_ms();
  const double quiet_for_ms = quiet_since ? now_ms - *quiet_since : 0;
  if (quiet_for_ms >= window_ms) return std::nullopt;
  if (!pausing_) {
    pausing_ = true;
    pause_since_ms_ = now_ms;
    ++(shared ? yields_ : listens_);
  }
  // Paused for as long as a starved deferral: the other does not pause for as long as we
  // wait (it never heard us, and only stops to listen). Our deferral's rules, starved by
  // now, take over and start us in its listening pause.
  if (now_ms - pause_since_ms_ >= kMaxDeferMs) return std::nullopt;
  return window_ms - quiet_for_ms;
}

double AirAccess::start_at(const CarrierSense& sense, double now_ms, AirUse use) {
  const std::optional<double> busy_ms = sense.last_busy_ms();
  if (use == AirUse::Stop) {
    answered_ = false;
    if (!stop_asked_ms_) stop_asked_ms_ = now_ms;
    if (!busy_ms || now_ms - *busy_ms >= kBusyNowMs) return now_ms;
    return std::min(*busy_ms + kBusyNowMs, *stop_asked_ms_ + kMaxStopWaitMs);
  }
  double at = not_before_ms_ ? std::max(now_ms, *not_before_ms_) : now_ms;
  if (use != AirUse::Renewal) {
    if (const auto left = pause_left_ms(sense, now_ms, shared(sense, now_ms))) at = now_ms + *left;
  }
  if (deferred_since_ms_ && !starved_ && now_ms - *deferred_since_ms_ >= kMaxDeferMs) {
    starved_ = true;
    backoff_ms_ = draw_backoff_ms(kStarvedSlots);
  }
  // Another's sound that ended with an answer we read was a whole exchange: nobody waits for
  // an answer on the air, and the quiet of a starved sender is enough.
  const bool answered = busy_ms && sense.answered_exchange_ms();
  const double hold_ms = starved_ || answered ? kStarvedQuietMs : quiet_ms_;
  answered_ = answered && !starved_;
  if (busy_ms && *busy_ms + hold_ms > now_ms && !backoff_ms_) {
    backoff_ms_ = draw_backoff_ms(kBackoffSlots);
    deferred_since_ms_ = now_ms;
    ++deferred_;
  }
  if (!backoff_ms_) return at;
  // Deferring: the quiet must be heard, our own tail fallen too (it may hide another).
  const std::optional<double> quiet_since = sense.quiet_since_ms();
  return std::max(at, (quiet_since ? *quiet_since : now_ms) + hold_ms + *backoff_ms_);
}

void AirAccess::started(const CarrierSense& sense, double at_ms) {
  const std::optional<double> quiet_since = sense.quiet_since_ms();
  // A new run after a pause, or after a quiet as long as a listening pause.
  if (!run_start_ms_ || pausing_ || (quiet_since && at_ms - *quiet_since >= kListenWindowMs)) run_start_ms_ = at_ms;
  if (backoff_ms_ && answered_) ++answered_waits_;
  answered_ = false;
  backoff_ms_.reset();
  deferred_since_ms_.reset();
  starved_ = false;
  pausing_ = false;
  pause_since_ms_ = 0;
  not_before_ms_.reset();
  stop_asked_ms_.reset();
}

void AirAccess::unanswered(const CarrierSense& sense, double at_ms) {
  if (shared(sense, at_ms)) not_before_ms_ = at_ms + draw_backoff_ms(kLossSlots);
}

}  // namespace dtmf::reliability
