#include "signal/bin_frame_listener.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtmf::signal {

BinFrameListener::BinFrameListener(const LinkProfile& profile)
    : bins_(profile.bins),
      sample_rate_hz_(profile.sample_rate_hz),
      hop_(profile.bins.hop_samples),
      hops_per_chord_(profile.bins.chord_samples() / profile.bins.hop_samples),
      gone_ratio_(static_cast<float>(std::pow(10.0, profile.bins.gone_db / 10.0))),
      presence_ratio_(static_cast<float>(std::pow(10.0, profile.bins.presence_db / 10.0))),
      bands_(profile.bins.window_samples, profile.bins.band_first_bin, profile.bins.tones_per_band,
             profile.bins.presence_db, profile.bins.dominance_db),
      window_(static_cast<std::size_t>(profile.bins.window_samples), static_cast<std::size_t>(profile.bins.hop_samples)) {
  if (profile.frame_format != FrameFormat::Command48 || bins_.chords_per_frame != 2 ||
      bins_.chord_samples() % hop_ != 0) {
    throw std::invalid_argument("profile '" + profile.name +
                                "' has no two-chord bin plan with chords a whole number of hops long");
  }
  ring_.resize(static_cast<std::size_t>(hops_per_chord_ + 1));
  for (WindowRecord& r : ring_) r.powers.assign(4 * static_cast<std::size_t>(bins_.tones_per_band), 0.0f);
  found_.reserve(16);
}

void BinFrameListener::reset() {
  window_.clear();
  for (WindowRecord& r : ring_) r.readings = {};
  windows_ = 0;
  analysed_until_ms_ = 0;
}

std::span<const FrameCandidate> BinFrameListener::feed(std::span<const float> samples) {
  found_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return found_;
}

// Each chord's tones must be gone from the other chord's window, band by band where both
// sound and differ: a tone still sounds when it is less than gone_db below that window's
// own tone and stands presence_db + gone_db out of the band's floor. (Noise alone in that
// bin is no tone: at -10 dB SNR a test at presence_db would throw away one frame in a
// hundred, since one noise bin in 500 reaches it.)
bool BinFrameListener::chords_apart(const WindowRecord& first, const WindowRecord& second) const {
  const auto tones = static_cast<std::size_t>(bins_.tones_per_band);
  auto sounding = [&](float power, const BandReading& band) {
    return power * gone_ratio_ > band.best && power > presence_ratio_ * gone_ratio_ * band.floor;
  };
  for (std::size_t b = 0; b < 4; ++b) {
    const BandReading& a = first.readings[b];
    const BandReading& z = second.readings[b];
    if (!a.present || !z.present || a.symbol == z.symbol) continue;
    if (sounding(second.powers[b * tones + a.symbol], z)) return false;
    if (sounding(first.powers[b * tones + z.symbol], a)) return false;
  }
  return true;
}

void BinFrameListener::analyze_window() {
  newest_ = (newest_ + 1) % ring_.size();
  WindowRecord& now = ring_[newest_];
  const auto readings = bands_.analyze(window_.window(), now.powers);
  std::copy(readings.begin(), readings.end(), now.readings.begin());
  ++windows_;
  analysed_until_ms_ = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
  if (windows_ <= hops_per_chord_) return;

  // The oldest record in the ring is exactly one chord before this one.
  const WindowRecord& first = ring_[(newest_ + 1) % ring_.size()];
  FrameCandidate c;
  for (std::size_t slot = 0; slot < kFrameBands; ++slot) {
    const BandReading& r = (slot < 4 ? first : now).readings[slot % 4];
    c.symbols[slot] = r.symbol;
    c.runner_up[slot] = r.runner_up;
    c.certainty[slot] = r.present ? r.certainty() : 1.0f;
    if (!r.present) ++c.absent;
  }
  if (c.absent > bins_.absent_bands || !chords_apart(first, now)) return;
  // A tone in both chords' windows: one chord seen twice, a held sound, or another profile's
  // chord. Senders never repeat a band's tone within a frame.
  for (std::size_t b = 0; b < 4; ++b) {
    if (first.readings[b].present && now.readings[b].present && c.symbols[b] == c.symbols[b + 4]) return;
  }
  const double ms_per_sample = 1000.0 / sample_rate_hz_;
  c.heard_ms = analysed_until_ms_;
  // The first chord's window started one chord and one window before now; the chord itself
  // began an edge (and up to a hop) before that window.
  c.start_ms = c.heard_ms - (bins_.chord_samples() + bins_.window_samples + bins_.edge_samples + hop_ / 2.0) * ms_per_sample;
  found_.push_back(c);
}

}  // namespace dtmf::signal
