#include "reliability/carrier_sense.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dtmf::reliability {

namespace {
// A block's (end_ms, level) joins the last kFloorSmoothMs of them.
void keep_recent(std::deque<std::pair<double, double>>& recent, double level_dbfs, double end_ms) {
  recent.emplace_back(end_ms, level_dbfs);
  while (recent.front().first <= end_ms - kFloorSmoothMs) recent.pop_front();
}

// The loudest of them: a tail's envelope.
double loudest_dbfs(const std::deque<std::pair<double, double>>& recent) {
  double envelope_dbfs = kSilenceDbfs;
  for (const auto& [at_ms, level] : recent) envelope_dbfs = std::max(envelope_dbfs, level);
  return envelope_dbfs;
}
}  // namespace

double block_level_dbfs(std::span<const float> samples) {
  if (samples.empty()) return kSilenceDbfs;
  double power = 0;
  for (const float s : samples) power += static_cast<double>(s) * s;
  power /= static_cast<double>(samples.size());
  // A full-scale sine has a mean power of 1/2.
  const double level = 10 * std::log10(2 * power);
  return std::isfinite(level) ? std::max(level, kSilenceDbfs) : kSilenceDbfs;
}

AirSpan own_answer_span(double frame_end_ms, std::optional<double> delay_ms, double max_delay_ms, double answer_ms) {
  const double from_ms = frame_end_ms + delay_ms.value_or(0);
  const double to_ms = frame_end_ms + delay_ms.value_or(max_delay_ms) + answer_ms;
  return {from_ms - kOwnLatencyMs, to_ms + kOwnLatencyMs};
}

void CarrierSense::own_begin(double) {
  own_on_ = true;
  answer_tail_open_ = false;  // what follows is ours
  waiting_ = false;
  provisional_.clear();
}

void CarrierSense::tail_from(double at_ms) {
  tail_from_ms_ = at_ms;
  tail_min_dbfs_ = std::numeric_limits<double>::infinity();
  tail_recent_.clear();
}

void CarrierSense::frame_ended(double at_ms) {
  if (!own_on_) return;
  own_on_ = false;
  waiting_ = true;
  tail_from(at_ms);
}

void CarrierSense::own_end(double at_ms, std::optional<AirSpan> answer) {
  if (!own_on_ && !waiting_) return;
  if (own_on_) tail_from(at_ms);
  own_on_ = waiting_ = false;
  own_ended_ms_ = at_ms;
  for (const auto& [busy_ms, over_db] : provisional_) {
    if (answer && busy_ms >= answer->from_ms && busy_ms <= answer->to_ms) continue;  // our robot's
    if (!last_busy_ms_ || busy_ms >= *last_busy_ms_) {
      last_busy_ms_ = busy_ms;
      last_busy_over_floor_db_ = over_db;
      last_busy_masked_ = false;
    }
    ++busy_blocks_;
  }
  provisional_.clear();
  // Our answer's tail follows; the frame's, if no answer came, goes on.
  if (answer) tail_from(at_ms);
}

bool CarrierSense::ours(double level_dbfs, double end_ms) {
  if (own_on_) return true;
  if (!tail_from_ms_) return false;
  const double since_ms = end_ms - *tail_from_ms_;
  if (since_ms >= kOwnTailMaxMs) return false;
  // Our sound may still be arriving for kOwnLatencyMs; after that, a rise over the tail's
  // quietest is someone else (or, while we wait, our robot's answer). The tail goes on under it.
  const bool arriving = since_ms < kOwnLatencyMs;
  if (!arriving && level_dbfs >= tail_min_dbfs_ + kBusyOverFloorDb) return false;
  // The tail's envelope: its loudest block of the last kFloorSmoothMs. A tone's decay in a
  // room beats (its modes interfere), so single blocks dip far under it and come back; the
  // envelope does not, yet follows a tail that ends at once (a flat air) within 20 ms. Not
  // while we wait: a sender's frame and its answer may leave less than 20 ms between them, an
  // envelope would then never fall, and a quieter sender would go unheard in every wait (on
  // the PulseAudio air, three senders started 2 to 3 times as many frames into another's).
  keep_recent(tail_recent_, level_dbfs, end_ms);
  const double envelope_dbfs = loudest_dbfs(tail_recent_);
  tail_min_dbfs_ = std::min(tail_min_dbfs_, waiting_ ? level_dbfs : envelope_dbfs);
  if (arriving) return true;
  // Fallen into the noise: the tail is over, and the air as quiet as it gets. Well under the
  // busy mark, so that a tail that flickers about it on its way down is not taken for another.
  if (!waiting_ && envelope_dbfs < floor_dbfs_ + kBusyOverFloorDb - kTailEndMarginDb) {
    tail_from_ms_.reset();
    return false;
  }
  return true;
}

double CarrierSense::follow_floor(double level_dbfs, double end_ms) {
  const double power = std::pow(10.0, level_dbfs / 10);
  if (!smoothed_power_ || !last_end_ms_) {
    smoothed_power_ = power;
  } else {
    // After our own sound, the smoothing resumes from the floor, over this block only: the
    // blocks our sound hid are the room's quiet, not a gap to bridge in one step (which
    // let a single block of noise stand for the whole 20 ms).
    const bool resumed = last_block_end_ms_ && *last_block_end_ms_ > *last_end_ms_;
    if (resumed) smoothed_power_ = std::pow(10.0, floor_dbfs_ / 10);
    const double from_ms = resumed ? *last_block_end_ms_ : *last_end_ms_;
    const double step = 1 - std::exp(-std::max(0.0, end_ms - from_ms) / kFloorSmoothMs);
    *smoothed_power_ += step * (power - *smoothed_power_);
  }
  last_end_ms_ = end_ms;
  const double smoothed_dbfs = std::max(10 * std::log10(*smoothed_power_), kSilenceDbfs);
  while (!minima_.empty() && minima_.back().second >= smoothed_dbfs) minima_.pop_back();
  minima_.emplace_back(end_ms, smoothed_dbfs);
  // A sender that sent for longer than the window heard nothing else: it keeps the last.
  while (minima_.size() > 1 && minima_.front().first < end_ms - kFloorWindowMs) minima_.pop_front();
  floor_dbfs_ = minima_.front().second;
  return smoothed_dbfs;
}

void CarrierSense::hear(double level_dbfs, double end_ms) {
  const bool ours_now = ours(level_dbfs, end_ms);
  // A sound: this block over the busy mark, and the last 20 ms too. One block of noise over
  // the mark is none (5 ms of pink noise at -50 dBFS passes it once in 20-30 s: a lone
  // sender then took the room for shared, and yielded for a minute).
  const double smoothed_dbfs = ours_now ? kSilenceDbfs : follow_floor(level_dbfs, end_ms);
  last_block_end_ms_ = end_ms;
  const double mark_dbfs = floor_dbfs_ + kBusyOverFloorDb;
  busy_now_ = !ours_now && level_dbfs >= mark_dbfs && smoothed_dbfs >= mark_dbfs;
  if (ours_now || busy_now_)
    quiet_since_ms_.reset();
  else if (!quiet_since_ms_)
    quiet_since_ms_ = end_ms;
  if (!ours_now) follow_answer_tail(level_dbfs, end_ms);
  if (!busy_now_) return;
  if (waiting_) {
    provisional_.emplace_back(end_ms, level_dbfs - floor_dbfs_);
    return;
  }
  last_busy_ms_ = end_ms;
  last_busy_over_floor_db_ = level_dbfs - floor_dbfs_;
  last_busy_masked_ = false;
  ++busy_blocks_;
}

// Another's answer's tail, judged as our own (ours()): on its envelope, since a tone's decay
// in a room beats; a sound rising over it is a new frame, whose answer someone awaits.
void CarrierSense::follow_answer_tail(double level_dbfs, double end_ms) {
  keep_recent(others_recent_, level_dbfs, end_ms);
  if (!answer_tail_open_) return;
  if (busy_now_ && level_dbfs >= answer_tail_min_dbfs_ + kBusyOverFloorDb) {
    answer_tail_open_ = false;
    return;
  }
  answer_tail_min_dbfs_ = std::min(answer_tail_min_dbfs_, loudest_dbfs(others_recent_));
}

void CarrierSense::answer_read(double end_ms) {
  if (own_on()) return;  // our robot's
  ++others_answers_;
  others_answer_ms_ = end_ms;
  answer_tail_open_ = true;
  while (!others_recent_.empty() && others_recent_.front().first <= end_ms - kFloorSmoothMs) others_recent_.pop_front();
  // The answer's own level: a frame that follows as loud is not yet told from its tail.
  answer_tail_min_dbfs_ = loudest_dbfs(others_recent_);
}

void CarrierSense::answer_masked(double end_ms) {
  ++masked_answers_;
  if (last_busy_ms_ && *last_busy_ms_ > end_ms) return;
  last_busy_ms_ = end_ms;
  last_busy_masked_ = true;
}

}  // namespace dtmf::reliability
