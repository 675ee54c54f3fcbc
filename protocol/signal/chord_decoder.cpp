#include "signal/chord_decoder.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dtmf::signal {

std::optional<ChordMatch> decode_chord(const TonePlan& plan, std::span<const Peak> peaks,
                                       double tolerance_hz) {
  std::array<int, 4> nibble{-1, -1, -1, -1};
  std::array<double, 4> level{};
  for (const Peak& peak : peaks) {
    const auto tone = match_plan_tone(plan, peak.frequency_hz, tolerance_hz);
    if (!tone) continue;
    const auto band = static_cast<std::size_t>(tone->band);
    if (nibble[band] >= 0 && nibble[band] != tone->nibble) return std::nullopt;  // two tones in one band
    nibble[band] = tone->nibble;
    level[band] = std::max(level[band], peak.amplitude);
  }
  std::uint16_t frame = 0;
  for (std::size_t band = 0; band < 4; ++band) {
    if (nibble[band] < 0) return std::nullopt;  // a band without a tone
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

std::optional<ReplyMatch> decode_reply(const TonePlan& plan, std::span<const Peak> peaks,
                                       double tolerance_hz) {
  const auto levels = [&](const std::array<double, 2>& tones) {
    return std::array<double, 2>{heard(peaks, tones[0], tolerance_hz), heard(peaks, tones[1], tolerance_hz)};
  };
  const auto ack = levels(plan.ack_hz);
  const auto nack = levels(plan.nack_hz);
  const bool ack_full = ack[0] > 0 && ack[1] > 0, ack_any = ack[0] > 0 || ack[1] > 0;
  const bool nack_full = nack[0] > 0 && nack[1] > 0, nack_any = nack[0] > 0 || nack[1] > 0;
  if (ack_full && !nack_any) return ReplyMatch{Reply::Ack, std::min(ack[0], ack[1])};
  if (nack_full && !ack_any) return ReplyMatch{Reply::Nack, std::min(nack[0], nack[1])};
  return std::nullopt;
}

}  // namespace dtmf::signal
