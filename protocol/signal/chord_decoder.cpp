#include "signal/chord_decoder.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "units/decibels.h"

namespace dtmf::signal {

namespace {

// The amplitude of the loudest peak within tolerance of `frequency_hz`, or 0.
double heard(std::span<const Peak> peaks, double frequency_hz, double tolerance_hz) {
  double level = 0;
  for (const Peak& peak : peaks) {
    if (std::abs(peak.frequency_hz - frequency_hz) <= tolerance_hz) level = std::max(level, peak.amplitude);
  }
  return level;
}

constexpr double kOffsetStepPpm = 100;  // 1.6 Hz at 16 kHz: fine beside a 25 Hz tolerance

double plan_tone_hz(const TonePlan& plan, const PlanTone& tone) {
  return plan.band_low_hz[static_cast<std::size_t>(tone.band)] + tone.nibble * plan.step_hz;
}

// Each peak's bands within reach under any offset up to `max_offset_ppm` (bit b for band b;
// 1 Hz of slack beside the rounding of f / scale): the offset search tries only those, 61
// offsets a window, where trying all four bands cost the seed receiver a third of its time.
// Peaks past the first kReachPeaks (more than any detector keeps) try every band.
constexpr std::size_t kReachPeaks = 32;
constexpr unsigned kAllBands = 0xF;
using PeakReach = std::array<unsigned, kReachPeaks>;

PeakReach reach_of(const TonePlan& plan, std::span<const Peak> peaks, const DetectorParams& rules) {
  PeakReach reach{};
  const double widest = rules.max_offset_ppm * 1e-6;
  for (std::size_t i = 0; i < std::min(peaks.size(), kReachPeaks); ++i) {
    const double hz = peaks[i].frequency_hz;
    reach[i] = bands_within_reach(plan, hz / (1.0 + widest) - 1.0, hz / (1.0 - widest) + 1.0, rules.tone_tolerance_hz);
  }
  return reach;
}

// How well the peaks, read through `scale`, sit on plan tones: each matching peak counts
// its amplitude, less the further it lies from its tone. The tone is match_plan_tone's (the
// first band's that matches), sought only in the bands within the peak's reach.
double plan_fit(const TonePlan& plan, std::span<const Peak> peaks, const PeakReach& reach, double scale,
                double tolerance_hz) {
  double fit = 0;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const unsigned bands = i < kReachPeaks ? reach[i] : kAllBands;
    if (bands == 0) continue;
    const double hz = peaks[i].frequency_hz / scale;
    for (int band = 0; band < 4; ++band) {
      if ((bands & (1u << band)) == 0) continue;
      if (const auto tone = match_band_tone(plan, band, hz, tolerance_hz)) {
        fit += peaks[i].amplitude * (1.0 - std::abs(hz - plan_tone_hz(plan, *tone)) / tolerance_hz);
        break;
      }
    }
  }
  return fit;
}

// The offset in ppm (0, +step, -step, +2 step, ...: the smallest wins a tie) under which
// the peaks fit the plan best.
double common_offset_ppm(const TonePlan& plan, std::span<const Peak> peaks, const PeakReach& reach,
                         const DetectorParams& rules) {
  double best_ppm = 0;
  double best_fit = plan_fit(plan, peaks, reach, 1.0, rules.tone_tolerance_hz);
  for (double ppm = kOffsetStepPpm; ppm <= rules.max_offset_ppm; ppm += kOffsetStepPpm) {
    for (const double signed_ppm : {ppm, -ppm}) {
      const double fit = plan_fit(plan, peaks, reach, 1.0 + signed_ppm * 1e-6, rules.tone_tolerance_hz);
      if (fit > best_fit) {
        best_fit = fit;
        best_ppm = signed_ppm;
      }
    }
  }
  return best_ppm;
}

}  // namespace

std::optional<ChordMatch> decode_chord(const TonePlan& plan, std::span<const Peak> peaks, const DetectorParams& rules) {
  const PeakReach reach = reach_of(plan, peaks, rules);
  // A band no peak can reach under any offset stays without a tone under every one.
  unsigned reached = peaks.size() > kReachPeaks ? kAllBands : 0;
  for (std::size_t i = 0; i < std::min(peaks.size(), kReachPeaks); ++i) reached |= reach[i];
  if (reached != kAllBands) return std::nullopt;
  const double offset_ppm = rules.max_offset_ppm > 0 ? common_offset_ppm(plan, peaks, reach, rules) : 0.0;
  const double scale = 1.0 + offset_ppm * 1e-6;
  const double ratio = units::amplitude_ratio_from_db(-rules.dominance_db);
  std::array<int, 4> nibble{-1, -1, -1, -1};
  std::array<double, 4> level{}, other{};  // the band's strongest tone, and its strongest other tone
  for (const Peak& peak : peaks) {
    const auto tone = match_plan_tone(plan, peak.frequency_hz / scale, rules.tone_tolerance_hz);
    if (!tone) continue;
    const auto band = static_cast<std::size_t>(tone->band);
    if (nibble[band] == tone->nibble || nibble[band] < 0) {
      nibble[band] = tone->nibble;
      level[band] = std::max(level[band], peak.amplitude);
    } else if (peak.amplitude > level[band]) {
      other[band] = level[band];
      nibble[band] = tone->nibble;
      level[band] = peak.amplitude;
    } else {
      other[band] = std::max(other[band], peak.amplitude);
    }
  }
  std::uint16_t frame = 0;
  for (std::size_t band = 0; band < 4; ++band) {
    if (nibble[band] < 0) return std::nullopt;                   // a band without a tone
    if (other[band] > level[band] * ratio) return std::nullopt;  // two tones in one band
    frame = static_cast<std::uint16_t>(frame | (nibble[band] << (12 - 4 * band)));
  }
  const double weakest = *std::min_element(level.begin(), level.end());
  if (rules.crowding_peaks > 0) {
    int crowd = 0;
    for (const Peak& peak : peaks) {
      const auto tone = match_plan_tone(plan, peak.frequency_hz / scale, rules.tone_tolerance_hz);
      const bool own = tone && nibble[static_cast<std::size_t>(tone->band)] == tone->nibble;
      if (!own && peak.amplitude >= weakest) ++crowd;
    }
    if (crowd >= rules.crowding_peaks) return std::nullopt;
  }
  return ChordMatch{frame, weakest, offset_ppm};
}

std::optional<ReplyMatch> decode_reply(const TonePlan& plan, std::span<const Peak> peaks, double tolerance_hz,
                                       double dominance_db) {
  const double ratio = units::amplitude_ratio_from_db(-dominance_db);
  const auto levels = [&](const std::array<double, 2>& tones) {
    return std::array<double, 2>{heard(peaks, tones[0], tolerance_hz), heard(peaks, tones[1], tolerance_hz)};
  };
  const auto ack = levels(plan.ack_hz);
  const auto nack = levels(plan.nack_hz);
  const double ack_level = std::min(ack[0], ack[1]), nack_level = std::min(nack[0], nack[1]);
  const double ack_any = std::max(ack[0], ack[1]), nack_any = std::max(nack[0], nack[1]);
  if (ack_level > 0 && nack_any <= ack_level * ratio) return ReplyMatch{Reply::Ack, ack_level};
  if (nack_level > 0 && ack_any <= nack_level * ratio) return ReplyMatch{Reply::Nack, nack_level};
  return std::nullopt;
}

}  // namespace dtmf::signal
