#include "signal/hop_listener.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dtmf::signal {

namespace {
// Hypotheses closer than this read the same bins over the whole plan: try one of them.
constexpr int kSameHypothesisPpm = 150;

int lowest_bin(const HopPlan& plan) {
  int lo = std::numeric_limits<int>::max();
  for (const auto& chord : plan.band_first_bin) lo = std::min(lo, *std::min_element(chord.begin(), chord.end()));
  return lo - HopReader::kMarginBins;
}

int end_bin(const HopPlan& plan) {
  int hi = 0;
  for (const auto& chord : plan.band_first_bin) hi = std::max(hi, *std::max_element(chord.begin(), chord.end()));
  const int top = hi + plan.tones_per_band;
  return top + HopReader::kMarginBins + static_cast<int>(std::ceil(top * plan.max_offset_ppm * 1e-6));
}

// A frame of the most chords and the window a chord before it, for as long as a re-read waits.
std::size_t history_windows(const HopPlan& plan) {
  return static_cast<std::size_t>(kMaxFrameChords * (plan.chord_samples() / plan.hop_samples) + 1 +
                                  plan.reread_delay_hops);
}
}  // namespace

HopListener::HopListener(const LinkProfile& profile)
    : hops_(profile.hops()),
      sample_rate_hz_(profile.sample_rate_hz),
      hop_(profile.hops().hop_samples),
      hops_per_chord_(profile.hops().chord_samples() / profile.hops().hop_samples),
      lo_bin_(lowest_bin(profile.hops())),
      hi_bin_(end_bin(profile.hops())),
      bins_(profile.hops().window_samples, lo_bin_, hi_bin_ - lo_bin_),
      window_(static_cast<std::size_t>(profile.hops().window_samples),
              static_cast<std::size_t>(profile.hops().hop_samples)),
      background_(SteadyBackground::for_power(
          static_cast<std::size_t>(hi_bin_ - lo_bin_), profile.hops().background_rise_db_per_s,
          static_cast<double>(profile.sample_rate_hz) / profile.hops().hop_samples)),
      history_(history_windows(profile.hops()), static_cast<std::size_t>(hi_bin_ - lo_bin_)),
      gate_(profile.hops(), lo_bin_),
      reader_(profile, lo_bin_, history_.size()),
      offset_(profile.hops()),
      rereads_(static_cast<long long>(profile.hops().reread_delay_hops) * profile.hops().hop_samples),
      whole_chords_(profile.hops(), lo_bin_, hi_bin_ - lo_bin_, kMaxFrameChords) {
  // A profile of another format was refused already: profile.hops() names it.
  if (hops_.chords_per_frame != 2 || hops_.chord_samples() % hop_ != 0) {
    throw std::invalid_argument("profile '" + profile.name +
                                "' has no two-chord hopped plan with chords a whole number of hops long");
  }
  for (ChordPowers& w : whole_chord_windows_) {
    w.power.assign(static_cast<std::size_t>(hi_bin_ - lo_bin_), 0.0f);
    w.excess.assign(static_cast<std::size_t>(hi_bin_ - lo_bin_), 0.0f);
  }
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

void HopListener::hold_until(double until_ms) {
  hold_until_ms_ = until_ms;
  phase_ = Phase::HoldFrame;
}

void HopListener::analyze_window(CandidateSink& sink) {
  HopWindow& now = history_.advance();
  bins_.analyze(window_.window(), now.power);
  if (hops_.reread_delay_hops > 0) whole_chords_.push(window_.window().last(static_cast<std::size_t>(hop_)));
  // A steady tone (a whine) becomes background within seconds, a chord's tone never does.
  background_.remove_power(now.power, now.excess);
  gate_.score(now);
  ++windows_;
  analysed_until_ms_ = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
  if (phase_ == Phase::HoldFrame && analysed_until_ms_ >= hold_until_ms_) phase_ = Phase::DetectFrame;
  if (phase_ == Phase::DetectFrame) {
    // Both shapes, even when the first took a frame (and put the listener on hold).
    for (int chords = 2; chords <= kMaxFrameChords; ++chords) {
      if (windows_ > (chords - 1) * hops_per_chord_) detect_frame(chords, sink);
    }
  }
  // After this window's own tries: a frame it takes needs no second look at the windows before.
  if (!rereads_.empty()) second_looks(sink);
}

HopListener::FrameWindows HopListener::frame_windows(int chords) const {
  FrameWindows w{};
  for (int c = -1; c < chords; ++c)
    w[static_cast<std::size_t>(c + 1)] = &history_.aged(static_cast<std::size_t>((chords - 1 - c) * hops_per_chord_));
  return w;
}

void HopListener::detect_frame(int chords, CandidateSink& sink) {
  const FrameWindows windows = frame_windows(chords);
  const auto chord_windows = std::span(windows).subspan(1, static_cast<std::size_t>(chords));
  const HopBandGate::Verdict verdict = gate_.judge(chord_windows);
  if (verdict == HopBandGate::Verdict::Closed) return;
  const long long now = window_.samples_fed();
  const std::optional<int> tracked = offset_.offset_ppm();
  if (verdict == HopBandGate::Verdict::RereadOnly) {
    // Too weak for the grid's readings to decode, maybe not for the whole chords: the sink
    // sees the reading (as a failed window) and says whether to read it again.
    if (sink.none_taken(make_candidate(chords, tracked.value_or(0), windows))) rereads_.keep(chords, now, {});
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
    offered_[count] = make_candidate(chords, ppm, windows);
    if (!sink.take(offered_[count++])) return false;
    taken_at_sample_ = now;
    return true;
  };
  if (tracked && offer(*tracked)) return;
  if (offer(0)) return;
  if (offer(reader_.blind_offset_ppm(chord_windows))) return;
  if (sink.none_taken(offered_[0])) rereads_.keep(chords, now, std::span(offered_).first(count));
}

HopCandidate HopListener::make_candidate(int chords, int offset_ppm, const FrameWindows& windows) const {
  std::array<const ChordPowers*, kMaxFrameChords + 1> powers{};
  std::copy(windows.begin(), windows.end(), powers.begin());
  HopCandidate c = reader_.read(chords, offset_ppm, std::span(powers).first(static_cast<std::size_t>(chords + 1)));
  const double ms_per_sample = 1000.0 / sample_rate_hz_;
  c.heard_ms = analysed_until_ms_;
  // The first chord's window started chords - 1 chords and one window before now; the chord
  // itself began an edge (and up to a hop) before that window.
  c.start_ms =
      c.heard_ms -
      ((chords - 1) * hops_.chord_samples() + hops_.window_samples + hops_.edge_samples + hop_ / 2.0) * ms_per_sample;
  // A window astride the first chord's start can decode a clean frame hops early: where its
  // tones rose says where it began.
  if (const auto start = reader_.first_chord_start_sample(c, history_, window_.samples_fed()))
    c.start_ms = static_cast<double>(*start) * ms_per_sample;
  return c;
}

// Queued windows whose delay has passed with no frame taken meanwhile: read again over each
// chord's whole steady part, then their grid hypotheses offered again (the sink may decode
// those harder now). A frame taken from one holds every window after it: the rest are dropped.
void HopListener::second_looks(CandidateSink& sink) {
  const long long now = window_.samples_fed();
  for (PendingWindow& p : rereads_.take_due(now, taken_at_sample_)) {
    bool taken = false;
    if (const auto c = read_whole_chords(p, now)) taken = sink.take(*c);
    for (std::size_t h = 0; h < p.hypotheses && !taken; ++h) {
      HopCandidate& g = p.grid[h];
      g.second_look = true;
      g.heard_ms = analysed_until_ms_;  // decided now
      taken = sink.take(g);
    }
    if (taken) {
      taken_at_sample_ = now;
      rereads_.clear();
      return;
    }
  }
}

std::optional<HopCandidate> HopListener::read_whole_chords(const PendingWindow& p, long long now) {
  // The grid window a chord before the frame's first, as its readings had it.
  const auto back = static_cast<std::size_t>((now - p.end_sample) / hop_ + p.chords * hops_per_chord_);
  if (back >= history_.size()) return std::nullopt;
  const HopWindow& before = history_.aged(back);
  const auto fit =
      whole_chords_.read(now - p.end_sample, p.chords, background_.background_power(), before.power,
                         std::span<ChordPowers>(whole_chord_windows_).first(static_cast<std::size_t>(p.chords + 1)));
  if (!fit) return std::nullopt;
  std::array<const ChordPowers*, kMaxFrameChords + 1> windows{};
  for (int c = 0; c <= p.chords; ++c)
    windows[static_cast<std::size_t>(c)] = &whole_chord_windows_[static_cast<std::size_t>(c)];
  // The reader read every bin at the offset already.
  HopCandidate c = reader_.read(p.chords, 0, std::span(windows).first(static_cast<std::size_t>(p.chords + 1)));
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

}  // namespace dtmf::signal
