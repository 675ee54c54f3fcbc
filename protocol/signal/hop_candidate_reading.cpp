// The fast profile's frame listener (hop_listener.h): how a candidate window is read — each
// band's tone and its certainty at an offset hypothesis, the offset a window's own peaks show,
// where the frame began, and the offset its decoded tones show (tracked for the frames after).
#include <algorithm>
#include <cmath>
#include <limits>

#include "signal/chord_onset.h"
#include "signal/hop_listener.h"
#include "signal/over_median.h"
#include "signal/peak_interpolation.h"

namespace dtmf::signal {

namespace {
constexpr int kOffsetStepPpm = 50;
// The most the middle half of a frame's tones may disagree on their offset to be tracked:
// a quarter bin at 10 kHz.
constexpr float kTrackSpreadPpm = 600.0f;
// A tone must stand this many times over its floor in amplitude to place its chord's start.
constexpr float kOnsetMinRise = 2.0f;
}  // namespace

// Every band's peak, to a fraction of a bin (a pure tone at p + d puts power in bins p and
// p + 1 in the ratio of sinc^2(d) to sinc^2(1 - d), so d = |X(p+1)| / (|X(p)| + |X(p+1)|));
// the offset is the one that brings most peaks nearest to whole bins (tones sit on bins).
int HopListener::blind_offset_ppm(int chords) const {
  std::array<float, kMaxFrameTones> position{}, weight{};
  for (int c = 0; c < chords; ++c) {
    const Window& w = chord_window(chords, c);
    const auto set = static_cast<std::size_t>(band_set(c));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const int lo = hops_.band_first_bin[set][static_cast<std::size_t>(b)] - lo_bin_ - kMarginBins + 1;
      const int n = hops_.tones_per_band + 2 * kMarginBins - 2;
      const auto* e = w.excess.data() + lo;
      const int p = static_cast<int>(std::max_element(e, e + n) - e);
      const float a0 = std::sqrt(std::max(e[p], 0.0f));
      const float am = std::sqrt(std::max(e[p - 1], 0.0f)), ap = std::sqrt(std::max(e[p + 1], 0.0f));
      const float d = ap > am ? ap / (a0 + ap + 1e-30f) : -am / (a0 + am + 1e-30f);
      const std::size_t t = static_cast<std::size_t>(tone_index(c, b));
      position[t] = static_cast<float>(lo_bin_ + lo + p) + d;
      const float score = w.band_score[static_cast<std::size_t>(tone_index(band_set(c), b))];
      weight[t] =
          std::clamp(std::log2(std::max(score, 1.0f)) - 2.0f, 0.0f, 10.0f);  // strong peaks count, noise does not
    }
  }
  int best_ppm = 0;
  float best_cost = std::numeric_limits<float>::max();
  for (int ppm = -hops_.max_offset_ppm; ppm <= hops_.max_offset_ppm; ppm += kOffsetStepPpm) {
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

HopCandidate HopListener::make_candidate(int chords, int offset_ppm) {
  std::array<const ChordPowers*, kMaxFrameChords + 1> windows{};
  for (int chord = -1; chord < chords; ++chord)
    windows[static_cast<std::size_t>(chord + 1)] = &chord_window(chords, chord);
  HopCandidate c = read_candidate(chords, offset_ppm, std::span(windows).first(static_cast<std::size_t>(chords + 1)));
  const double ms_per_sample = 1000.0 / sample_rate_hz_;
  c.heard_ms = analysed_until_ms_;
  // The first chord's window started chords - 1 chords and one window before now; the chord
  // itself began an edge (and up to a hop) before that window.
  c.start_ms =
      c.heard_ms -
      ((chords - 1) * hops_.chord_samples() + hops_.window_samples + hops_.edge_samples + hop_ / 2.0) * ms_per_sample;
  // A window astride the first chord's start can decode a clean frame hops early: where its
  // tones rose says where it began.
  if (const auto start = first_chord_start_sample(c)) c.start_ms = static_cast<double>(*start) * ms_per_sample;
  return c;
}

std::optional<long long> HopListener::first_chord_start_sample(const HopCandidate& c) const {
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
    const ToneReading& r = c.tones[static_cast<std::size_t>(tone_index(0, b))];
    if (!r.heard) continue;
    const auto bin = static_cast<std::size_t>(
        std::lround((hops_.band_first_bin[0][static_cast<std::size_t>(b)] + r.symbol) * scale) - lo_bin_);
    for (int k = 0; k <= back; ++k) {
      const Window& w = ring_[(newest_ + ring_.size() - static_cast<std::size_t>(back - k)) % ring_.size()];
      windows[static_cast<std::size_t>(k)] = std::sqrt(std::max(w.excess[bin], 0.0f));
    }
    if (const auto steady = chord_steady_start(windows, hops_.window_samples, hop_, kOnsetMinRise)) {
      earliest = std::min(earliest, *steady);
      ++placed;
    }
  }
  if (placed < HopPlan::kBandsPerChord / 2) return std::nullopt;
  const long long floor_window_start =
      window_.samples_fed() - static_cast<long long>(back) * hop_ - hops_.window_samples;
  const long long start = floor_window_start + std::llround(earliest) - hops_.edge_samples;
  // Only where the grid's windows could have read the frame from: the first chord's window
  // wholly inside it (with a hop to spare), or astride its start.
  const long long grid_window_start = floor_window_start + static_cast<long long>(hops_per_chord_) * hop_;
  if (start < grid_window_start - 2 * hop_ - hops_.edge_samples || start > grid_window_start + hops_.window_samples) {
    return std::nullopt;
  }
  return start;
}

HopCandidate HopListener::read_candidate(int chords, int offset_ppm,
                                         std::span<const ChordPowers* const> windows) const {
  HopCandidate c;
  c.chords = chords;
  c.offset_ppm = offset_ppm;
  const double scale = 1.0 + offset_ppm * 1e-6;
  for (int chord = 0; chord < chords; ++chord) {
    const ChordPowers& w = *windows[static_cast<std::size_t>(chord + 1)];
    const ChordPowers& before = *windows[static_cast<std::size_t>(chord)];
    const auto set = static_cast<std::size_t>(band_set(chord));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const std::size_t t = static_cast<std::size_t>(tone_index(chord, b));
      scratch_.clear();
      floor_.clear();
      int best = 0, second_best = -1;
      int best_bin = 0;
      for (int v = 0; v < hops_.tones_per_band; ++v) {
        // A tone moved between two bins splits its power between them: take both then.
        const double at = (hops_.band_first_bin[set][static_cast<std::size_t>(b)] + v) * scale;
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

void HopListener::confirm(const HopCandidate& candidate, std::span<const std::uint8_t> symbols) {
  // Each tone sent on bin f was heard at f (1 + offset): the median over the tones the
  // decoder did not have to correct.
  std::array<float, kMaxFrameTones> offsets{};
  std::size_t n = 0;
  for (int chord = 0; chord < candidate.chords; ++chord) {
    const auto set = static_cast<std::size_t>(band_set(chord));
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      const std::size_t t = static_cast<std::size_t>(tone_index(chord, b));
      if (t >= symbols.size() || candidate.tones[t].symbol != symbols[t] || !candidate.tones[t].heard) continue;
      const float sent_bin = static_cast<float>(hops_.band_first_bin[set][static_cast<std::size_t>(b)] + symbols[t]);
      offsets[n++] = (candidate.peak_bins[t] / sent_bin - 1.0f) * 1e6f;
    }
  }
  if (n < 8) return;
  std::sort(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(n));
  const float median = offsets[n / 2];
  // Only a window wholly inside both chords gives every tone's true position; one that
  // straddles a chord's edge smears each tone over its neighbours, and the two-bin estimate
  // then errs by up to half a bin either way. Such windows decode too (the code corrects),
  // but their offsets scatter: track only an estimate whose middle half agrees.
  const float spread = offsets[3 * n / 4] - offsets[n / 4];
  if (spread > kTrackSpreadPpm) return;
  tracked_ppm_ = static_cast<int>(std::lround(median));
}

}  // namespace dtmf::signal
