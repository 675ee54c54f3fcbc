#include "signal/whole_chord_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dtmf::signal {

namespace {
constexpr int kPadding = 4;         // the reading FFT is kPadding * W points: quarter-bin steps
constexpr int kSearchPadding = 2;   // the start search's FFT: half bins, at half the cost
constexpr int kCoarseSteps = 4;     // the start search's coarse step, in reread_step_samples
constexpr int kOffsetStepPpm = 50;  // a sixth of a quarter bin at 17.5 kHz
constexpr int kCoarseOffsetPpm = 250;
constexpr float kOffsetMargin = 1.05f;  // 0.2 dB
}  // namespace

WholeChordReader::WholeChordReader(const HopPlan& hops, int lo_bin, int bins, int max_chords)
    : hops_(hops),
      lo_bin_(lo_bin),
      bins_(bins),
      steady_samples_(hops.window_samples + hops.hop_samples),
      first_padded_bin_(static_cast<std::size_t>(
          std::max(1.0, std::floor(kPadding * lo_bin * (1.0 - hops.max_offset_ppm * 1e-6)) - 2))),
      first_search_bin_(static_cast<std::size_t>(kSearchPadding * lo_bin)),
      // How far the largest offset moves the top band's last tone (2.1 bins at 17.5 kHz).
      search_margin_bins_([&] {
        int top = 0;
        for (const auto& set : hops.band_first_bin) top = std::max(top, *std::max_element(set.begin(), set.end()));
        return static_cast<int>(std::ceil((top + hops.tones_per_band) * hops.max_offset_ppm * 1e-6));
      }()),
      unit_(static_cast<float>(std::pow(static_cast<double>(hops.window_samples) / steady_samples_, 2))),
      fft_(kPadding * hops.window_samples, static_cast<int>(first_padded_bin_),
           static_cast<int>(std::ceil(kPadding * (lo_bin + bins) * (1.0 + hops.max_offset_ppm * 1e-6))) + 2 -
               static_cast<int>(first_padded_bin_),
           Weighting::Rectangular, Planning::Estimated),
      search_fft_(kSearchPadding * hops.window_samples, static_cast<int>(first_search_bin_), kSearchPadding * bins,
                  Weighting::Rectangular, Planning::Estimated),
      // The oldest read: a frame of the most chords, a hop of search before it, and the delay
      // after its last grid window.
      history_(static_cast<std::size_t>(max_chords * hops.chord_samples() + hops.window_samples +
                                        (hops.reread_delay_hops + 2) * hops.hop_samples)),
      padded_(static_cast<std::size_t>(kPadding * hops.window_samples), 0.0f),
      search_padded_(static_cast<std::size_t>(kSearchPadding * hops.window_samples), 0.0f),
      search_power_(static_cast<std::size_t>(search_fft_.bins()), 0.0f),
      chord_power_(static_cast<std::size_t>(max_chords), std::vector<float>(static_cast<std::size_t>(fft_.bins()))) {
  if (hops.reread_delay_hops > 0 && (hops.reread_step_samples < 1 || hops.tones_per_band % 4 != 0))
    throw std::invalid_argument(
        "whole-chord re-reads need reread_step_samples >= 1 and tones_per_band a multiple of 4");
}

void WholeChordReader::push(std::span<const float> samples) {
  // In at most two copies: no division per sample (every hop pushes one).
  while (!samples.empty()) {
    const std::size_t at = written_ % history_.size();
    const std::size_t n = std::min(samples.size(), history_.size() - at);
    std::copy_n(samples.begin(), n, history_.begin() + static_cast<std::ptrdiff_t>(at));
    samples = samples.subspan(n);
    written_ += n;
  }
}

void WholeChordReader::add_steady(long long start, std::span<float> padded) const {
  // The ring holds the stream's sample i at i % size: at most two pieces.
  const std::size_t n = history_.size();
  const std::size_t from = static_cast<std::size_t>(start) % n;
  const std::size_t first = std::min(n - from, static_cast<std::size_t>(steady_samples_));
  const float* a = history_.data() + from;
  for (std::size_t i = 0; i < first; ++i) padded[i] += a[i];
  for (std::size_t i = first; i < static_cast<std::size_t>(steady_samples_); ++i) padded[i] += history_[i - first];
}

void WholeChordReader::transform(long long start, std::span<float> power) {
  std::fill_n(padded_.begin(), steady_samples_, 0.0f);
  add_steady(start, padded_);
  fft_.analyze(padded_, power);
}

std::size_t WholeChordReader::padded_bin(int bin, float step) const {
  // Single precision: bins below 3000 land within 0.001 of where double would put them.
  return static_cast<std::size_t>(static_cast<float>(bin) * step + 0.5f) - first_padded_bin_;
}

float WholeChordReader::grid_power(std::span<const float> power, int bin, double scale) const {
  return power[padded_bin(bin, static_cast<float>(kPadding * scale))] * unit_;
}

float WholeChordReader::strongest_tones(std::span<const float> power, int chord, double scale) const {
  // Run for every offset tried (about 35 a re-read): four running maxima, so that no maximum
  // waits for the one before it.
  const auto step = static_cast<float>(kPadding * scale);
  float sum = 0;
  for (const int first : hops_.band_first_bin[static_cast<std::size_t>(chord % 2)]) {
    std::array<float, 4> top{};
    for (int v = 0; v + 3 < hops_.tones_per_band; v += 4) {
      for (int k = 0; k < 4; ++k)
        top[static_cast<std::size_t>(k)] =
            std::max(top[static_cast<std::size_t>(k)], power[padded_bin(first + v + k, step)]);
    }
    sum += std::max(std::max(top[0], top[1]), std::max(top[2], top[3]));
  }
  return sum * unit_;
}

float WholeChordReader::start_score(long long start, int chords) {
  // The chords' steady parts summed: their bands are disjoint (chords alternate band sets),
  // so one transform shows every chord's tones, at twice the noise in each band.
  std::fill_n(search_padded_.begin(), steady_samples_, 0.0f);
  for (int c = 0; c < chords; ++c) add_steady(start + c * hops_.chord_samples(), search_padded_);
  search_fft_.analyze(search_padded_, search_power_);
  // Each band's strongest half bin, tones moved by an offset included.
  float score = 0;
  for (int set = 0; set < std::min(chords, 2); ++set) {
    for (const int first : hops_.band_first_bin[static_cast<std::size_t>(set)]) {
      const auto lo = static_cast<std::size_t>(kSearchPadding * (first - search_margin_bins_)) - first_search_bin_;
      const auto hi = static_cast<std::size_t>(kSearchPadding * (first + hops_.tones_per_band + search_margin_bins_)) -
                      first_search_bin_;
      score += *std::max_element(search_power_.begin() + static_cast<std::ptrdiff_t>(lo),
                                 search_power_.begin() + static_cast<std::ptrdiff_t>(hi));
    }
  }
  return score;
}

std::optional<WholeChordFit> WholeChordReader::read(long long age, int chords, std::span<const float> background,
                                                    std::span<const float> before, std::span<ChordPowers> out) {
  const long long newest_end = static_cast<long long>(written_);
  const long long chord = hops_.chord_samples();
  const long long hop = hops_.hop_samples;
  // Chord 0's grid window began here; its steady part began at most a hop before it.
  const long long window0 = newest_end - age - hops_.window_samples - (chords - 1) * chord;
  const long long oldest = window0 - hop;
  if (oldest < 0 || oldest < newest_end - history_samples() ||
      window0 + (chords - 1) * chord + steady_samples_ > newest_end)
    return std::nullopt;
  // Where the steady parts begin: the most power in the bands' strongest half bins, first in
  // coarse steps (kCoarseSteps steps) over the hop, then in steps within half a coarse step of
  // the best. The measure falls off steadily either side of the true start, so the coarse
  // grid's best lies within half a coarse step of it.
  const long long step = hops_.reread_step_samples;
  long long start = window0;
  float best = -1;
  const auto consider = [&](long long at) {
    at = std::clamp(at, window0 - hop, window0);
    const float score = start_score(at, chords);
    if (score > best) {
      best = score;
      start = at;
    }
  };
  for (long long back = 0; back < hop + kCoarseSteps * step; back += kCoarseSteps * step) consider(window0 - back);
  const long long coarse = start;
  for (long long d = -(kCoarseSteps / 2) * step; d <= (kCoarseSteps / 2) * step; d += step) {
    if (d != 0) consider(coarse + d);
  }
  for (int c = 0; c < chords; ++c) transform(start + c * chord, chord_power_[static_cast<std::size_t>(c)]);
  // The offset: the most power in the bands' strongest tones, over every offset the listener
  // searches, coarsely and then finely around the best.
  const auto offset_score = [&](int ppm) {
    float score = 0;
    for (int c = 0; c < chords; ++c)
      score += strongest_tones(chord_power_[static_cast<std::size_t>(c)], c, 1.0 + ppm * 1e-6);
    return score;
  };
  int offset_ppm = 0;
  const float at_none = offset_score(0);
  best = at_none;
  for (int ppm = -hops_.max_offset_ppm; ppm <= hops_.max_offset_ppm; ppm += kCoarseOffsetPpm) {
    if (const float score = offset_score(ppm); score > best) {
      best = score;
      offset_ppm = ppm;
    }
  }
  const int coarse_ppm = offset_ppm;
  for (int ppm = coarse_ppm - kCoarseOffsetPpm + kOffsetStepPpm; ppm < coarse_ppm + kCoarseOffsetPpm;
       ppm += kOffsetStepPpm) {
    if (ppm == coarse_ppm || std::abs(ppm) > hops_.max_offset_ppm) continue;
    if (const float score = offset_score(ppm); score > best) {
      best = score;
      offset_ppm = ppm;
    }
  }
  // No offset unless another reads more by a margin: noise may favour a neighbouring offset by
  // a hair. A real offset of 400 ppm, read as none, loses up to 2.4 dB on the top bands' tones
  // (a quarter bin off), about 1 dB over all bands: far over the margin.
  if (best < kOffsetMargin * at_none) offset_ppm = 0;
  const double scale = 1.0 + offset_ppm * 1e-6;
  for (int c = -1; c < chords; ++c) {
    ChordPowers& o = out[static_cast<std::size_t>(c + 1)];
    for (int i = 0; i < bins_; ++i) {
      const int bin = lo_bin_ + i;
      // The grid bin the tone falls in: a whine's background lies there, and so does its
      // power in the grid window a chord before the frame.
      const auto at = static_cast<std::size_t>(std::clamp<long>(std::lround(bin * scale) - lo_bin_, 0, bins_ - 1));
      const float p = c < 0 ? before[at] : grid_power(chord_power_[static_cast<std::size_t>(c)], bin, scale);
      o.power[static_cast<std::size_t>(i)] = p;
      o.excess[static_cast<std::size_t>(i)] = std::max(0.0f, p - background[at]);
    }
  }
  return WholeChordFit{offset_ppm, newest_end - start};
}

}  // namespace dtmf::signal
