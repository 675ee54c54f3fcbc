#include "signal/hop_tag_listener.h"

#include <algorithm>
#include <cmath>

#include "signal/hop_candidate.h"
#include "signal/over_median.h"
#include "units/decibels.h"

namespace dtmf::signal {

namespace {

// Bins read beyond the bands at either end: the largest offset moves the top band's tones by
// about a bin.
constexpr int kMarginBins = 3;

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
      hops_per_chord_(profile.hops().chord_samples() / profile.hops().hop_samples),
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
  power_ring_.assign(static_cast<std::size_t>(hops_per_chord_ + 1),
                     std::vector<float>(static_cast<std::size_t>(bins_.bins()), 0.0f));
  heard_.reserve(16);
}

std::span<const HeardTagChord> HopTagListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

void HopTagListener::read_band(int offset, int band, const std::vector<float>& power, const std::vector<float>& before,
                               std::array<std::int8_t, reliability::kTagChordCandidates>& out) const {
  out.fill(-1);
  const auto from =
      static_cast<std::size_t>(first_bin_[static_cast<std::size_t>(offset)][static_cast<std::size_t>(band)]);
  const auto powers = std::span<const float>(power).subspan(from, static_cast<std::size_t>(hops_.tones_per_band));
  std::array<float, reliability::kTagChordCandidates> level{};
  for (int v = 0; v < hops_.tones_per_band; ++v) {
    const float p = powers[static_cast<std::size_t>(v)];
    if (!(p > onset_ratio_ * before[from + static_cast<std::size_t>(v)])) continue;
    // Insert v among the strongest so far.
    int at = reliability::kTagChordCandidates;
    while (at > 0 && (out[static_cast<std::size_t>(at - 1)] < 0 || level[static_cast<std::size_t>(at - 1)] < p)) --at;
    if (at == reliability::kTagChordCandidates) continue;
    for (int i = reliability::kTagChordCandidates - 1; i > at; --i) {
      out[static_cast<std::size_t>(i)] = out[static_cast<std::size_t>(i - 1)];
      level[static_cast<std::size_t>(i)] = level[static_cast<std::size_t>(i - 1)];
    }
    out[static_cast<std::size_t>(at)] = static_cast<std::int8_t>(v);
    level[static_cast<std::size_t>(at)] = p;
  }
  // Only candidates that stand over the band's floor count; they are sorted, so cut at the first that does not.
  for (int i = 0; i < reliability::kTagChordCandidates; ++i) {
    if (out[static_cast<std::size_t>(i)] >= 0 &&
        !over_median(powers, level[static_cast<std::size_t>(i)], presence_ratio_)) {
      for (int j = i; j < reliability::kTagChordCandidates; ++j) out[static_cast<std::size_t>(j)] = -1;
      break;
    }
  }
}

void HopTagListener::analyze_window() {
  newest_ = (newest_ + 1) % power_ring_.size();
  std::vector<float>& power = power_ring_[newest_];
  bins_.analyze(window_.window(), power);
  ++windows_;
  if (windows_ <= hops_per_chord_) return;  // the stream is taken to be preceded by silence
  const std::vector<float>& before = power_ring_[(newest_ + 1) % power_ring_.size()];  // a chord earlier
  HeardTagChord h;
  for (int o = 0; o < HopPlan::kTagOffsets; ++o) {
    for (int k = 0; k < reliability::kTagChordTones; ++k)
      read_band(o, k, power, before, h.reading[static_cast<std::size_t>(o)][static_cast<std::size_t>(k)]);
  }
  if (reliability::tag_chord_heard(h.reading) < reliability::kTagChordMatchesNeeded) return;
  h.window = windows_;
  h.heard_ms = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
  heard_.push_back(h);
}

}  // namespace dtmf::signal
