#include "signal/hop_reply.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "signal/over_median.h"
#include "units/decibels.h"

namespace dtmf::signal {

namespace {
constexpr int kMarginBins = 2;
}  // namespace

HopReplyListener::HopReplyListener(const LinkProfile& profile, int min_heard)
    : hops_(profile.hops()),
      min_heard_(min_heard),
      sample_rate_hz_(profile.sample_rate_hz),
      presence_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().reply_presence_db))),
      onset_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().reply_onset_db))),
      lo_bin_(std::min(profile.hops().reply_bin(0, 0, 0), profile.hops().reply_bin(HopPlan::kReplyLanes - 1, 0, 0)) -
              kMarginBins),
      hops_per_chord_(profile.hops().reply_chord_samples() / profile.hops().reply_hop_samples),
      bins_(profile.hops().reply_window_samples, lo_bin_,
            std::max(profile.hops().reply_bin(0, HopPlan::kReplyBands - 1, HopPlan::kReplyToneValues - 1),
                     profile.hops().reply_bin(HopPlan::kReplyLanes - 1, HopPlan::kReplyBands - 1,
                                              HopPlan::kReplyToneValues - 1)) +
                kMarginBins + 1 - lo_bin_,
            Weighting::Hann),
      window_(static_cast<std::size_t>(profile.hops().reply_window_samples),
              static_cast<std::size_t>(profile.hops().reply_hop_samples)),
      background_(SteadyBackground::for_power(
          static_cast<std::size_t>(bins_.bins()), profile.hops().reply_background_rise_db_per_s,
          static_cast<double>(profile.sample_rate_hz) / profile.hops().reply_hop_samples)) {
  if (profile.hops().reply_chord_samples() % profile.hops().reply_hop_samples != 0) {
    throw std::invalid_argument("profile '" + profile.name + "': a reply chord must be a whole number of reply hops");
  }
  const auto bins = static_cast<std::size_t>(bins_.bins());
  power_ring_.assign(static_cast<std::size_t>(2 * hops_per_chord_ + 1), std::vector<float>(bins, 0.0f));
  excess_ring_ = power_ring_;
  heard_.reserve(64);  // a reading per window and lane: 40 in a block of 4096 samples
}

std::span<const HeardReading> HopReplyListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

// Band `band`'s tone in lane `lane` in a window: the strongest of its bins that rose since
// `before` (tone `exclude` aside), or -1 when none rose or the strongest that did stands too
// little over the band's floor.
int HopReplyListener::read_band(const std::vector<float>& excess, const std::vector<float>& power,
                                const std::vector<float>& before, int lane, int band, int exclude) {
  int best = -1;
  float best_excess = 0;
  for (int v = 0; v < hops_.reply_tones_per_band; ++v) {
    const auto at = static_cast<std::size_t>(hops_.reply_bin(lane, band, v) - lo_bin_);
    if (v != exclude && power[at] > onset_ratio_ * before[at] && (best < 0 || excess[at] > best_excess)) {
      best = v;
      best_excess = excess[at];
    }
  }
  if (best < 0) return -1;
  // The band's floor: the median of the raw power of its bins, from its first tone to its
  // last (the tones and the bins between them).
  const auto from = static_cast<std::size_t>(hops_.reply_bin(lane, band, 0) - lo_bin_);
  const auto to = static_cast<std::size_t>(hops_.reply_bin(lane, band, hops_.reply_tones_per_band - 1) + 1 - lo_bin_);
  return over_median(std::span<const float>(power).subspan(from, to - from), best_excess, presence_ratio_) ? best : -1;
}

void HopReplyListener::analyze_window() {
  newest_ = (newest_ + 1) % power_ring_.size();
  std::vector<float>& power = power_ring_[newest_];
  std::vector<float>& excess = excess_ring_[newest_];
  bins_.analyze(window_.window(), power);
  background_.remove_power(power, excess);
  ++windows_;
  if (windows_ <= 2 * hops_per_chord_) return;  // the stream is taken to be preceded by silence
  const std::size_t first =
      (newest_ + power_ring_.size() - static_cast<std::size_t>(hops_per_chord_)) % power_ring_.size();
  const std::size_t before = (newest_ + 1) % power_ring_.size();  // two chords ago: before the reply
  for (int lane = 0; lane < HopPlan::kReplyLanes; ++lane) read_lane(lane, first, before);
}

void HopReplyListener::read_lane(int lane, std::size_t first, std::size_t before) {
  HeardReading r;
  r.lane = lane;
  for (int chord = 0; chord < HopPlan::kReplyChords; ++chord) {
    const std::size_t w = chord == 0 ? first : newest_;
    // The second chord's tones must rise over the first chord's window, and a band's tone of
    // the first chord is no tone of the second: no reply repeats it (reply_code.h), and in a
    // room it rings on into the second chord, its reverberation often louder than when it
    // was read.
    const std::size_t reference = chord == 0 ? before : first;
    for (int b = 0; b < HopPlan::kReplyBands; ++b) {
      const int exclude = chord == 0 ? -1 : r.tones[static_cast<std::size_t>(b)];
      const int tone = read_band(excess_ring_[w], power_ring_[w], power_ring_[reference], lane, b, exclude);
      r.tones[static_cast<std::size_t>(chord * HopPlan::kReplyBands + b)] = tone;
      r.heard += tone >= 0 ? 1 : 0;
    }
  }
  if (r.heard < min_heard_) return;
  r.window = windows_;
  const double ms_per_sample = 1000.0 / sample_rate_hz_;
  r.heard_ms = static_cast<double>(window_.samples_fed()) * ms_per_sample;
  r.start_ms = r.heard_ms - (hops_.reply_chord_samples() + hops_.reply_window_samples + hops_.reply_edge_samples +
                             hops_.reply_hop_samples / 2.0) *
                                ms_per_sample;
  heard_.push_back(r);
}

}  // namespace dtmf::signal
