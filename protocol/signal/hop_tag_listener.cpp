#include "signal/hop_tag_listener.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "signal/hop_candidate.h"
#include "units/decibels.h"

namespace dtmf::signal {

namespace {

// Bins read beyond the bands at either end: the largest offset moves the top band's tones by
// about a bin.
constexpr int kMarginBins = 3;
constexpr int kMaxTonesPerBand = 64;

int band_first_bin(const HopPlan& h, int band) {
  return h.band_first_bin[static_cast<std::size_t>(band / HopPlan::kBandsPerChord)]
                         [static_cast<std::size_t>(band % HopPlan::kBandsPerChord)];
}

int lowest_bin(const HopPlan& h) {
  int lo = band_first_bin(h, 0);
  for (int k = 0; k < reliability::kTagChordTones; ++k) lo = std::min(lo, band_first_bin(h, k));
  return lo - kMarginBins;
}

int highest_bin(const HopPlan& h) {
  int hi = 0;
  for (int k = 0; k < reliability::kTagChordTones; ++k) hi = std::max(hi, band_first_bin(h, k) + h.tones_per_band - 1);
  return hi + kMarginBins;
}

}  // namespace

HopTagListener::HopTagListener(const LinkProfile& profile)
    : hops_(profile.hops()),
      sample_rate_hz_(profile.sample_rate_hz),
      presence_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().tag_presence_db))),
      onset_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().tag_onset_db))),
      lo_bin_(lowest_bin(profile.hops())),
      first_clear_hops_((profile.hops().window_samples + profile.hops().hop_samples - 1) / profile.hops().hop_samples),
      bins_(profile.hops().window_samples, lo_bin_, highest_bin(profile.hops()) + 1 - lo_bin_),
      window_(static_cast<std::size_t>(profile.hops().window_samples),
              static_cast<std::size_t>(profile.hops().hop_samples)) {
  for (int o = 0; o < HopPlan::kTagOffsets; ++o) {
    const double scale = 1.0 + 1e-6 * hops_.tag_offset_ppm[static_cast<std::size_t>(o)];
    for (int k = 0; k < reliability::kTagChordTones; ++k) {
      // A band spans 32 bins; at the largest offset its tones move together to within 0.05 bin.
      const double centre = band_first_bin(hops_, k) + (hops_.tones_per_band - 1) / 2.0;
      const int shift = static_cast<int>(std::lround(centre * scale - centre));
      first_bin_[static_cast<std::size_t>(o)][static_cast<std::size_t>(k)] = band_first_bin(hops_, k) + shift - lo_bin_;
    }
  }
  if (hops_.tones_per_band > kMaxTonesPerBand) throw std::invalid_argument("tones_per_band is over 64");
  if (hops_.tag_onset_lookback_hops < first_clear_hops_)
    throw std::invalid_argument("tag_onset_lookback_hops must reach past a window's length");
  power_ring_.assign(static_cast<std::size_t>(hops_.tag_onset_lookback_hops + 1),
                     std::vector<float>(static_cast<std::size_t>(bins_.bins()), 0.0f));
  quietest_.assign(static_cast<std::size_t>(bins_.bins()), 0.0f);
  heard_.reserve(16);
}

std::span<const HeardTagChord> HopTagListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

void HopTagListener::read_band(int offset, int band, const std::vector<float>& power,
                               const std::vector<float>& quietest,
                               std::array<std::int8_t, reliability::kTagChordCandidates>& out) const {
  out.fill(-1);
  const auto from =
      static_cast<std::size_t>(first_bin_[static_cast<std::size_t>(offset)][static_cast<std::size_t>(band)]);
  const auto powers = std::span<const float>(power).subspan(from, static_cast<std::size_t>(hops_.tones_per_band));
  // The band's floor: its median power (over_median's test, made once for the band).
  std::array<float, kMaxTonesPerBand> sorted{};
  const auto n = powers.size();
  std::copy(powers.begin(), powers.end(), sorted.begin());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(n / 2), sorted.begin() + static_cast<long>(n));
  const float floor = presence_ratio_ * sorted[n / 2];
  std::array<float, reliability::kTagChordCandidates> rise{};
  for (int v = 0; v < hops_.tones_per_band; ++v) {
    const float p = powers[static_cast<std::size_t>(v)];
    const float q = quietest[from + static_cast<std::size_t>(v)];
    if (!(p > floor && p > onset_ratio_ * q)) continue;
    // Ranked by how much it rose: a tail that rings on beside the answer (the sender's own
    // frame's, spread by the room's reflections of its end) rose less than the answer did.
    const float r = p - q;
    int at = reliability::kTagChordCandidates;
    while (at > 0 && (out[static_cast<std::size_t>(at - 1)] < 0 || rise[static_cast<std::size_t>(at - 1)] < r)) --at;
    if (at == reliability::kTagChordCandidates) continue;
    for (int i = reliability::kTagChordCandidates - 1; i > at; --i) {
      out[static_cast<std::size_t>(i)] = out[static_cast<std::size_t>(i - 1)];
      rise[static_cast<std::size_t>(i)] = rise[static_cast<std::size_t>(i - 1)];
    }
    out[static_cast<std::size_t>(at)] = static_cast<std::int8_t>(v);
    rise[static_cast<std::size_t>(at)] = r;
  }
}

void HopTagListener::analyze_window() {
  newest_ = (newest_ + 1) % power_ring_.size();
  std::vector<float>& power = power_ring_[newest_];
  bins_.analyze(window_.window(), power);
  ++windows_;
  const auto lookback = static_cast<long long>(hops_.tag_onset_lookback_hops);
  if (windows_ <= lookback) return;  // the stream is taken to be preceded by silence
  const std::size_t ring = power_ring_.size();
  quietest_ = power_ring_[(newest_ + ring - static_cast<std::size_t>(first_clear_hops_)) % ring];
  for (long long k = first_clear_hops_ + 1; k <= lookback; ++k) {
    const std::vector<float>& earlier = power_ring_[(newest_ + ring - static_cast<std::size_t>(k)) % ring];
    for (std::size_t b = 0; b < quietest_.size(); ++b) quietest_[b] = std::min(quietest_[b], earlier[b]);
  }
  HeardTagChord h;
  for (int o = 0; o < HopPlan::kTagOffsets; ++o) {
    for (int k = 0; k < reliability::kTagChordTones; ++k)
      read_band(o, k, power, quietest_, h.reading[static_cast<std::size_t>(o)][static_cast<std::size_t>(k)]);
  }
  if (reliability::tag_chord_heard(h.reading) < reliability::kTagChordMatchesNeeded) return;
  h.window = windows_;
  h.heard_ms = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
  heard_.push_back(h);
}

}  // namespace dtmf::signal
