#include "signal/hop_listener.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "units/decibels.h"

namespace dtmf::signal {

namespace {
// Hypotheses closer than this read the same bins over the whole plan: try one of them.
constexpr int kSameHypothesisPpm = 150;
}  // namespace

HopListener::HopListener(const LinkProfile& profile)
    : hops_(profile.hops()),
      sample_rate_hz_(profile.sample_rate_hz),
      hop_(profile.hops().hop_samples),
      hops_per_chord_(profile.hops().chord_samples() / profile.hops().hop_samples),
      presence_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().presence_db))),
      onset_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().onset_db))),
      gate_ratio_(static_cast<float>(units::power_ratio_from_db(profile.hops().gate_db))),
      lo_bin_([&] {
        int lo = std::numeric_limits<int>::max();
        for (const auto& chord : profile.hops().band_first_bin)
          lo = std::min(lo, *std::min_element(chord.begin(), chord.end()));
        return lo - kMarginBins;
      }()),
      hi_bin_([&] {
        int hi = 0;
        for (const auto& chord : profile.hops().band_first_bin)
          hi = std::max(hi, *std::max_element(chord.begin(), chord.end()));
        const int top = hi + profile.hops().tones_per_band;
        return top + kMarginBins + static_cast<int>(std::ceil(top * profile.hops().max_offset_ppm * 1e-6));
      }()),
      bins_(profile.hops().window_samples, lo_bin_, hi_bin_ - lo_bin_),
      window_(static_cast<std::size_t>(profile.hops().window_samples),
              static_cast<std::size_t>(profile.hops().hop_samples)),
      background_(SteadyBackground::for_power(
          static_cast<std::size_t>(hi_bin_ - lo_bin_), profile.hops().background_rise_db_per_s,
          static_cast<double>(profile.sample_rate_hz) / profile.hops().hop_samples)),
      reread_(profile.hops(), lo_bin_, hi_bin_ - lo_bin_, kMaxFrameChords) {
  // A profile of another format was refused already: profile.hops() names it.
  if (hops_.chords_per_frame != 2 || hops_.chord_samples() % hop_ != 0) {
    throw std::invalid_argument("profile '" + profile.name +
                                "' has no two-chord hopped plan with chords a whole number of hops long");
  }
  const auto bins = static_cast<std::size_t>(hi_bin_ - lo_bin_);
  // A frame of the most chords and the window a chord before it, for as long as a re-read waits.
  ring_.resize(static_cast<std::size_t>(kMaxFrameChords * hops_per_chord_ + 1 + hops_.reread_delay_hops));
  for (Window& w : ring_) {
    w.power.assign(bins, 0.0f);
    w.excess.assign(bins, 0.0f);
  }
  onset_amplitude_.assign(ring_.size(), 0.0f);
  for (ChordPowers& w : reread_windows_) {
    w.power.assign(bins, 0.0f);
    w.excess.assign(bins, 0.0f);
  }
  scratch_.reserve(static_cast<std::size_t>(hops_.tones_per_band));
  floor_.reserve(static_cast<std::size_t>(hops_.tones_per_band));
  found_.reserve(192);  // three hypotheses of two shapes a window, 32 windows (a 16 000-sample block) a feed
}

std::span<const HopCandidate> HopListener::feed(std::span<const float> samples) {
  // A sink that takes nothing, so that every hypothesis is built, and keeps them all.
  struct Collect final : CandidateSink {
    std::vector<HopCandidate>& found;
    explicit Collect(std::vector<HopCandidate>& f) : found(f) {}
    bool take(const HopCandidate& c) override {
      found.push_back(c);
      return false;
    }
    bool none_taken(const HopCandidate&) override { return true; }
  } collect(found_);
  found_.clear();
  feed(samples, collect);
  return found_;
}

void HopListener::feed(std::span<const float> samples, CandidateSink& sink) {
  window_.feed(samples, [&] { analyze_window(sink); });
}

void HopListener::analyze_window(CandidateSink& sink) {
  newest_ = (newest_ + 1) % ring_.size();
  Window& now = ring_[newest_];
  bins_.analyze(window_.window(), now.power);
  if (hops_.reread_delay_hops > 0) reread_.push(window_.window().last(static_cast<std::size_t>(hop_)));
  // A steady tone (a whine) becomes background within seconds, a chord's tone never does.
  background_.remove_power(now.power, now.excess);
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      // The band's best excess (a whine is background, not excess) over the mean of the
      // other bins' raw power (the excess is zero wherever a bin just fell to a new low, so
      // its mean is no floor to measure noise against).
      const std::size_t from = static_cast<std::size_t>(
          hops_.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] - lo_bin_ - 2);
      const int n = hops_.tones_per_band + 4;
      float best = 0, sum = 0;
      std::size_t at = from;
      for (std::size_t i = from; i < from + static_cast<std::size_t>(n); ++i) {
        if (now.excess[i] > best) {
          best = now.excess[i];
          at = i;
        }
        sum += now.power[i];
      }
      const float others = (sum - now.power[at]) / static_cast<float>(n - 1);
      now.band_score[static_cast<std::size_t>(tone_index(c, b))] = best / std::max(others, 1e-30f);
    }
  }
  ++windows_;
  analysed_until_ms_ = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
  if (analysed_until_ms_ >= hold_until_ms_) {
    for (int chords = 2; chords <= kMaxFrameChords; ++chords) {
      if (windows_ > (chords - 1) * hops_per_chord_) offer_shape(chords, sink);
    }
  }
  // After this window's own tries: a frame it takes needs no second look at the windows before.
  if (pending_count_ > 0) reread_pending(sink);
}

const HopListener::Window& HopListener::chord_window(int chords, int c) const {
  const auto back = static_cast<std::size_t>((chords - 1 - c) * hops_per_chord_);
  return ring_[(newest_ + ring_.size() - back) % ring_.size()];
}

void HopListener::offer_shape(int chords, CandidateSink& sink) {
  const Gate passed = gate(chords);
  if (passed == Gate::Closed) return;
  if (passed == Gate::RereadOnly) {
    // Too weak for the grid's readings to decode, maybe not for the whole chords: the sink
    // sees the reading (as a failed window) and says whether to read it again.
    if (sink.none_taken(make_candidate(chords, tracked_ppm_.value_or(0)))) keep_for_reread(chords, {});
    return;
  }
  std::array<int, kOffsetHypotheses> tried{};
  std::size_t count = 0;
  // Builds and offers the hypothesis unless one like it was tried; true when taken.
  const auto offer = [&](int ppm) {
    for (std::size_t i = 0; i < count; ++i) {
      if (std::abs(tried[i] - ppm) < kSameHypothesisPpm) return false;
    }
    tried[count] = ppm;
    offered_[count] = make_candidate(chords, ppm);
    if (!sink.take(offered_[count++])) return false;
    taken_at_sample_ = window_.samples_fed();
    return true;
  };
  if (tracked_ppm_ && offer(*tracked_ppm_)) return;
  if (offer(0)) return;
  if (offer(blind_offset_ppm(chords))) return;
  if (sink.none_taken(offered_[0])) keep_for_reread(chords, std::span(offered_).first(count));
}

void HopListener::keep_for_reread(int chords, std::span<const HopCandidate> hypotheses) {
  if (hops_.reread_delay_hops <= 0 || pending_count_ == pending_.size()) return;
  Pending& p = pending_[pending_count_++];
  p.chords = chords;
  p.end_sample = window_.samples_fed();
  p.hypotheses = hypotheses.size();
  std::copy(hypotheses.begin(), hypotheses.end(), p.grid.begin());
}

// Pending windows whose delay has passed with no frame taken meanwhile get a second look:
// read again over each chord's whole steady part, then their grid hypotheses offered again
// (the sink may decode those harder now); a window that a frame was taken in or after is
// dropped (the frame was its own, or holds the windows after it).
void HopListener::reread_pending(CandidateSink& sink) {
  const long long now = window_.samples_fed();
  const long long delay = static_cast<long long>(hops_.reread_delay_hops) * hop_;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending_count_; ++i) {
    Pending& p = pending_[i];
    if (taken_at_sample_ >= p.end_sample) continue;
    if (now - p.end_sample < delay) {
      if (kept != i) pending_[kept] = p;
      ++kept;
      continue;
    }
    bool taken = false;
    if (const auto c = read_whole_chords(p, now)) taken = sink.take(*c);
    for (std::size_t h = 0; h < p.hypotheses && !taken; ++h) {
      HopCandidate& g = p.grid[h];
      g.second_look = true;
      g.heard_ms = analysed_until_ms_;  // decided now
      taken = sink.take(g);
    }
    if (taken) taken_at_sample_ = now;
  }
  pending_count_ = kept;
}

std::optional<HopCandidate> HopListener::read_whole_chords(const Pending& p, long long now) {
  // The grid window a chord before the frame's first, as its readings had it.
  const auto back = static_cast<std::size_t>((now - p.end_sample) / hop_ + p.chords * hops_per_chord_);
  if (back >= ring_.size()) return std::nullopt;
  const Window& before = ring_[(newest_ + ring_.size() - back) % ring_.size()];
  const auto fit = reread_.read(now - p.end_sample, p.chords, background_.background_power(), before.power,
                                std::span<ChordPowers>(reread_windows_).first(static_cast<std::size_t>(p.chords + 1)));
  if (!fit) return std::nullopt;
  std::array<const ChordPowers*, kMaxFrameChords + 1> windows{};
  for (int c = 0; c <= p.chords; ++c)
    windows[static_cast<std::size_t>(c)] = &reread_windows_[static_cast<std::size_t>(c)];
  // The reader read every bin at the offset already.
  HopCandidate c = read_candidate(p.chords, 0, std::span(windows).first(static_cast<std::size_t>(p.chords + 1)));
  c.whole_chords = true;
  c.second_look = true;
  c.offset_ppm = fit->offset_ppm;
  for (std::size_t t = 0; t < c.tone_count(); ++t) c.peak_bins[t] *= static_cast<float>(1.0 + fit->offset_ppm * 1e-6);
  // Heard now, when the robot can act on it; begun where the re-read found the first chord
  // (its fade before its steady part), closer than the grid's half a hop.
  c.heard_ms = analysed_until_ms_;
  c.start_ms =
      analysed_until_ms_ - static_cast<double>(fit->steady_start_age + hops_.edge_samples) * 1000.0 / sample_rate_hz_;
  return c;
}

// Half or more of each chord's eight bands stand out of their own means: a frame, or something loud
// and tonal enough in every band set to be worth decoding. A noise band scores 6.2 dB on
// average (1.5 dB spread), a frame's at -10 dB SNR about 12. Every chord must: one chord's
// bands loud and the next one's silent is a frame's edge, or the next frame's first chord.
// Short of that, but with `reread_gate_bands` in every chord and half of all the bands, a
// window is only worth a whole-chord re-read: at -12 dB a frame's weaker chord misses the gate
// by a band in 1 % of frames, and the grid's readings of such a window seldom decode.
HopListener::Gate HopListener::gate(int chords) const {
  // Counted, not summed: two loud tones (a seed chord, a whistle) must not carry a chord
  // whose other bands hold nothing.
  int weakest = HopPlan::kBandsPerChord, total = 0;
  for (int c = 0; c < chords; ++c) {
    const Window& w = chord_window(chords, c);
    int loud = 0;
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b)
      loud += w.band_score[static_cast<std::size_t>(tone_index(band_set(c), b))] >= gate_ratio_ ? 1 : 0;
    weakest = std::min(weakest, loud);
    total += loud;
  }
  if (weakest >= hops_.gate_bands) return Gate::Open;
  const bool reread = hops_.reread_delay_hops > 0 && weakest >= hops_.reread_gate_bands &&
                      total >= chords * HopPlan::kBandsPerChord / 2;
  return reread ? Gate::RereadOnly : Gate::Closed;
}

}  // namespace dtmf::signal
