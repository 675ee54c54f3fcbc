#include "signal/hop_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "signal/chord_onset.h"
#include "signal/over_median.h"
#include "signal/peak_interpolation.h"
#include "units/decibels.h"

namespace dtmf::signal {

namespace {
constexpr int kOffsetStepPpm = 50;
// A tone must stand this many times over its floor in amplitude to place its chord's start.
constexpr float kOnsetMinRise = 2.0f;
}  // namespace

HopReader::HopReader(const LinkProfile& profile, int lo_bin, std::size_t history_windows)
    : plan_(profile.hops()),
      lo_bin_(lo_bin),
      hop_(profile.hops().hop_samples),
      hops_per_chord_(profile.hops().chord_samples() / profile.hops().hop_samples),
      presence_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().presence_db))),
      onset_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().onset_db))) {
  scratch_.reserve(static_cast<std::size_t>(plan_.tones_per_band));
  floor_.reserve(static_cast<std::size_t>(plan_.tones_per_band));
  onset_amplitude_.assign(history_windows, 0.0f);
}

// Every band's peak, to a fraction of a bin (a pure tone at p + d puts power in bins p and
// p + 1 in the ratio of sinc^2(d) to sinc^2(1 - d), so d = |X(p+1)| / (|X(p)| + |X(p+1)|));
// the offset is the one that brings most peaks nearest to whole bins (tones sit on bins).
int HopReader::blind_offset_ppm(std::span<const HopWindow* const> chord_windows) const {
  const int chords = static_cast<int>(chord_windows.size());
  std::array<float, kMaxFrameTones> position{}, weight{};
  for (int c = 0; c < chords; ++c) {
    const HopWindow& w = *chord_windows[static_cast<std::size_t>(c)];
    const auto set = static_cast<std::size_t>(hop_band_set(c));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const int lo = plan_.band_first_bin[set][static_cast<std::size_t>(b)] - lo_bin_ - kMarginBins + 1;
      const int n = plan_.tones_per_band + 2 * kMarginBins - 2;
      const auto* e = w.excess.data() + lo;
      const int p = static_cast<int>(std::max_element(e, e + n) - e);
      const float a0 = std::sqrt(std::max(e[p], 0.0f));
      const float am = std::sqrt(std::max(e[p - 1], 0.0f)), ap = std::sqrt(std::max(e[p + 1], 0.0f));
      const float d = ap > am ? ap / (a0 + ap + 1e-30f) : -am / (a0 + am + 1e-30f);
      const std::size_t t = static_cast<std::size_t>(hop_tone_index(c, b));
      position[t] = static_cast<float>(lo_bin_ + lo + p) + d;
      const float score = w.band_score[static_cast<std::size_t>(hop_tone_index(hop_band_set(c), b))];
      weight[t] =
          std::clamp(std::log2(std::max(score, 1.0f)) - 2.0f, 0.0f, 10.0f);  // strong peaks count, noise does not
    }
  }
  int best_ppm = 0;
  float best_cost = std::numeric_limits<float>::max();
  for (int ppm = -plan_.max_offset_ppm; ppm <= plan_.max_offset_ppm; ppm += kOffsetStepPpm) {
    const float scale = 1.0f / (1.0f + static_cast<float>(ppm) * 1e-6f);
    float cost = 0;
    for (std::size_t t = 0; t < static_cast<std::size_t>(chords * HopPlan::kBandsPerChord); ++t) {
      const float at = position[t] * scale;
      const float r = at - std::round(at);
      cost += weight[t] * std::min(r * r, 0.06f);
    }
    if (cost < best_cost - 1e-6f || (cost <= best_cost + 1e-6f && std::abs(ppm) < std::abs(best_ppm))) {
      best_cost = cost;
      best_ppm = ppm;
    }
  }
  return best_ppm;
}

std::optional<long long> HopReader::first_chord_start_sample(const HopCandidate& c, const HopWindowHistory& history,
                                                             long long samples_fed) const {
  // The windows from the one a chord before the frame's first (the floor) to the newest.
  const int back = c.chords * hops_per_chord_;
  const double scale = 1.0 + c.offset_ppm * 1e-6;
  // Each heard tone's own rise: in a room a tone's plateau holds its reverberant build-up as
  // well as the direct sound, so where the reverberation outweighs the direct sound (the
  // measured rooms hold 5-13 dB more than it) its half-plateau comes up to tens of ms late.
  // The direct sound reaches every tone at once: the earliest tone's rise is the start.
  std::size_t placed = 0;
  double earliest = std::numeric_limits<double>::max();
  const auto windows = std::span(onset_amplitude_).first(static_cast<std::size_t>(back + 1));
  for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
    const ToneReading& r = c.tones[static_cast<std::size_t>(hop_tone_index(0, b))];
    if (!r.heard) continue;
    const auto bin = static_cast<std::size_t>(
        std::lround((plan_.band_first_bin[0][static_cast<std::size_t>(b)] + r.symbol) * scale) - lo_bin_);
    for (int k = 0; k <= back; ++k) {
      const HopWindow& w = history.aged(static_cast<std::size_t>(back - k));
      windows[static_cast<std::size_t>(k)] = std::sqrt(std::max(w.excess[bin], 0.0f));
    }
    if (const auto steady = chord_steady_start(windows, plan_.window_samples, hop_, kOnsetMinRise)) {
      earliest = std::min(earliest, *steady);
      ++placed;
    }
  }
  if (placed < HopPlan::kBandsPerChord / 2) return std::nullopt;
  const long long floor_window_start = samples_fed - static_cast<long long>(back) * hop_ - plan_.window_samples;
  const long long start = floor_window_start + std::llround(earliest) - plan_.edge_samples;
  // Only where the grid's windows could have read the frame from: the first chord's window
  // wholly inside it (with a hop to spare), or astride its start.
  const long long grid_window_start = floor_window_start + static_cast<long long>(hops_per_chord_) * hop_;
  if (start < grid_window_start - 2 * hop_ - plan_.edge_samples || start > grid_window_start + plan_.window_samples) {
    return std::nullopt;
  }
  return start;
}

HopCandidate HopReader::read(int chords, int offset_ppm, std::span<const ChordPowers* const> windows) const {
  HopCandidate c;
  c.chords = chords;
  c.offset_ppm = offset_ppm;
  const double scale = 1.0 + offset_ppm * 1e-6;
  for (int chord = 0; chord < chords; ++chord) {
    const ChordPowers& w = *windows[static_cast<std::size_t>(chord + 1)];
    const ChordPowers& before = *windows[static_cast<std::size_t>(chord)];
    const auto set = static_cast<std::size_t>(hop_band_set(chord));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const std::size_t t = static_cast<std::size_t>(hop_tone_index(chord, b));
      scratch_.clear();
      floor_.clear();
      int best = 0, second_best = -1;
      int best_bin = 0;
      for (int v = 0; v < plan_.tones_per_band; ++v) {
        // A tone moved between two bins splits its power between them: take both then.
        const double at = (plan_.band_first_bin[set][static_cast<std::size_t>(b)] + v) * scale;
        const int bin = static_cast<int>(std::lround(at));
        const double frac = at - bin;
        const auto i = static_cast<std::size_t>(bin - lo_bin_);
        float value = w.excess[i];
        float power = w.power[i];
        if (std::abs(frac) > 0.25) {
          value += w.excess[frac > 0 ? i + 1 : i - 1];
          power += w.power[frac > 0 ? i + 1 : i - 1];
        }
        scratch_.push_back(value);
        floor_.push_back(power);
        if (v == 0 || value > scratch_[static_cast<std::size_t>(best)]) {
          second_best = v == 0 ? -1 : best;
          best = v;
          best_bin = bin;
        } else if (second_best < 0 || value > scratch_[static_cast<std::size_t>(second_best)]) {
          second_best = v;
        }
      }
      const float top = scratch_[static_cast<std::size_t>(best)];
      const float runner = scratch_[static_cast<std::size_t>(second_best)];
      const auto bi = static_cast<std::size_t>(best_bin - lo_bin_);
      ToneReading& r = c.tones[t];
      r.symbol = static_cast<std::uint8_t>(best);
      r.runner_up = second_best;
      r.certainty = runner > 0 ? top / runner : 1e9f;
      r.risen = w.power[bi] > onset_ratio_ * before.power[bi];
      // Heard: over the band's floor, the median of its raw power (the excess is zero at many bins).
      r.heard = over_median(floor_, top, presence_ratio_) && r.risen;
      // The peak to a fraction of a bin, for offset tracking once the frame is known.
      const float a0 = std::sqrt(std::max(w.excess[bi], 0.0f));
      const float am = std::sqrt(std::max(w.excess[bi - 1], 0.0f)), ap = std::sqrt(std::max(w.excess[bi + 1], 0.0f));
      c.peak_bins[t] = static_cast<float>(best_bin) + rectangular_peak_offset(am, a0, ap);
    }
  }
  return c;
}

}  // namespace dtmf::signal
