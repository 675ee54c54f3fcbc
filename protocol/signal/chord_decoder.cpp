#include "signal/chord_decoder.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dtmf::signal {

std::optional<ChordMatch> decode_chord(const TonePlan& plan, std::span<const Peak> peaks, double tolerance_hz,
                                       double dominance_db) {
  const double ratio = std::pow(10.0, -dominance_db / 20.0);
  std::array<int, 4> nibble{-1, -1, -1, -1};
  std::array<double, 4> level{}, other{};  // the band's strongest tone, and its strongest other tone
  for (const Peak& peak : peaks) {
    const auto tone = match_plan_tone(plan, peak.frequency_hz, tolerance_hz);
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
    if (nibble[band] < 0) return std::nullopt;                // a band without a tone
    if (other[band] > level[band] * ratio) return std::nullopt;  // two tones in one band
    frame = static_cast<std::uint16_t>(frame | (nibble[band] << (12 - 4 * band)));
  }
  return ChordMatch{frame, *std::min_element(level.begin(), level.end())};
}

namespace {

// The amplitude of the loudest peak within tolerance of `frequency_hz`, or 0.
double heard(std::span<const Peak> peaks, double frequency_hz, double tolerance_hz) {
  double level = 0;
  for (const Peak& peak : peaks) {
    if (std::abs(peak.frequency_hz - frequency_hz) <= tolerance_hz) level = std::max(level, peak.amplitude);
  }
  return level;
}

}  // namespace

std::optional<ReplyMatch> decode_reply(const TonePlan& plan, std::span<const Peak> peaks, double tolerance_hz,
                                       double dominance_db) {
  const double ratio = std::pow(10.0, -dominance_db / 20.0);
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
