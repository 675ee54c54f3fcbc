#include "reliability/air_access.h"

#include <algorithm>
#include <cmath>

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

namespace {
// What the carrier sense last heard, as the reason a frame waits for it.
AirWaitReason heard(const CarrierSense& sense) {
  if (sense.answered_exchange_ms()) return {AirWaitCause::AnsweredExchange};
  if (sense.last_busy_masked()) return {AirWaitCause::MaskedAnswer};
  return {AirWaitCause::Sound, sense.last_busy_over_floor_db()};
}
}  // namespace

std::string air_wait_text(const AirWaitReason& reason) {
  switch (reason.cause) {
    case AirWaitCause::None:
      return "";
    case AirWaitCause::Sound:
      return "sound " + std::to_string(static_cast<int>(std::lround(reason.over_floor_db))) +
             " dB over the room's floor";
    case AirWaitCause::AnsweredExchange:
      return "another sender's exchange (its robot's answer was heard)";
    case AirWaitCause::MaskedAnswer:
      return "another sender's robot answered under our last frame";
    case AirWaitCause::Yield:
      return "yielding to another sender";
    case AirWaitCause::Listen:
      return "listening for another sender that may be waiting";
    case AirWaitCause::LossBackoff:
      return "backing off after an unanswered frame in a shared room";
  }
  return "";
}

double AirAccess::start_at(const CarrierSense& sense, double now_ms, AirUse use, AirWait& wait) {
  bound_start_.reset();
  // Spent: the command goes out into whatever sounds, and says so by waiting no more.
  const bool stop = use == AirUse::Stop || use == AirUse::EveryRobotStop;
  if (!stop && wait.held_ms >= kMaxDeferToUnknownMs) return now_ms;
  AirWaitReason why;
  const double at = rules_at(sense, now_ms, use, why);
  if (!stop) bound_start_ = false;
  if (at <= now_ms) return at;
  if (!wait.since_ms) {
    wait.since_ms = now_ms;
    wait.reason = why;
  }
  // A stop has a bound of its own, per frame (kMaxStopWaitMs).
  if (stop) return at;
  const double bound_at = now_ms + std::max(0.0, kMaxDeferToUnknownMs - wait.total_ms(now_ms));
  bound_start_ = bound_at <= now_ms;
  return std::min(at, bound_at);
}

double AirAccess::stop_at(const CarrierSense& sense, double now_ms, AirWaitReason& why) {
  const std::optional<double> busy_ms = sense.last_busy_ms();
  answered_ = false;
  if (!stop_asked_ms_) stop_asked_ms_ = now_ms;
  if (!busy_ms || now_ms - *busy_ms >= kBusyNowMs) return now_ms;
  why = heard(sense);
  return std::min(*busy_ms + kBusyNowMs, *stop_asked_ms_ + kMaxStopWaitMs);
}

double AirAccess::rules_at(const CarrierSense& sense, double now_ms, AirUse use, AirWaitReason& why) {
  if (use == AirUse::EveryRobotStop) return now_ms;
  if (use == AirUse::Stop) return stop_at(sense, now_ms, why);
  const std::optional<double> busy_ms = sense.last_busy_ms();
  const std::optional<double> quiet_since = sense.quiet_since_ms();
  // The sound our last wait outlasted has ended once the air is heard quiet for the hold.
  if (held_over_ && quiet_since && now_ms - *quiet_since >= quiet_ms_) held_over_ = false;
  if (held_over_) starved_ = true;
  double at = now_ms;
  if (not_before_ms_ && *not_before_ms_ > now_ms) {
    at = *not_before_ms_;
    why = {AirWaitCause::LossBackoff};
  }
  if (use != AirUse::Renewal) {
    const bool is_shared = shared(sense, now_ms);
    if (const auto left = pause_left_ms(sense, now_ms, is_shared)) {
      at = now_ms + *left;
      why = {is_shared ? AirWaitCause::Yield : AirWaitCause::Listen};
    }
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
  // Held over, the quiet must be heard anew: our own exchange since deafened us to the sound.
  const bool unheard = held_over_ && (!quiet_since || now_ms - *quiet_since < hold_ms);
  if (((busy_ms && *busy_ms + hold_ms > now_ms) || unheard) && !backoff_ms_) {
    backoff_ms_ = draw_backoff_ms(starved_ ? kStarvedSlots : kBackoffSlots);
    deferred_since_ms_ = now_ms;
    ++deferred_;
  }
  if (!backoff_ms_) return at;
  // Deferring: the quiet must be heard, our own tail fallen too (it may hide another).
  const double deferred_at = (quiet_since ? *quiet_since : now_ms) + hold_ms + *backoff_ms_;
  if (deferred_at <= at) return at;
  why = heard(sense);
  return deferred_at;
}

void AirAccess::started(const CarrierSense& sense, double at_ms, AirWait& wait) {
  wait.last_ms = wait.since_ms ? at_ms - *wait.since_ms : 0;
  if (wait.since_ms) {
    wait.held_ms += wait.last_ms;
    ++wait.waits;
  }
  wait.since_ms.reset();
  const bool by_the_bound = bound_start_.value_or(false);
  if (bound_start_) held_over_ = *bound_start_;
  bound_start_.reset();
  const std::optional<double> quiet_since = sense.quiet_since_ms();
  // A new run after a pause, or after a quiet as long as a listening pause, or after the
  // bound ended a wait (no frame of ours held the air for kMaxDeferToUnknownMs: a run of
  // ours counted from before it would make the next frame yield, and miss the listening
  // pause of a sender that never heard us).
  if (!run_start_ms_ || pausing_ || by_the_bound || (quiet_since && at_ms - *quiet_since >= kListenWindowMs))
    run_start_ms_ = at_ms;
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
