#include "signal/chord_decoder.h"

#include <array>
#include <cmath>

namespace dtmf::signal {

std::optional<std::uint16_t> decode_chord(const TonePlan& plan, std::span<const Peak> peaks,
                                          double tolerance_hz) {
  std::array<int, 4> nibble{-1, -1, -1, -1};
  for (const Peak& peak : peaks) {
    const auto tone = match_plan_tone(plan, peak.frequency_hz, tolerance_hz);
    if (!tone) continue;
    int& slot = nibble[static_cast<std::size_t>(tone->band)];
    if (slot >= 0 && slot != tone->nibble) return std::nullopt;  // two tones in one band
    slot = tone->nibble;
  }
  std::uint16_t frame = 0;
  for (int band = 0; band < 4; ++band) {
    const int value = nibble[static_cast<std::size_t>(band)];
    if (value < 0) return std::nullopt;  // a band without a tone
    frame = static_cast<std::uint16_t>(frame | (value << (12 - 4 * band)));
  }
  return frame;
}

namespace {
bool heard(std::span<const Peak> peaks, double frequency_hz, double tolerance_hz) {
  for (const Peak& peak : peaks) {
    if (std::abs(peak.frequency_hz - frequency_hz) <= tolerance_hz) return true;
  }
  return false;
}

bool all_heard(std::span<const Peak> peaks, const std::array<double, 2>& tones, double tolerance_hz) {
  return heard(peaks, tones[0], tolerance_hz) && heard(peaks, tones[1], tolerance_hz);
}

bool any_heard(std::span<const Peak> peaks, const std::array<double, 2>& tones, double tolerance_hz) {
  return heard(peaks, tones[0], tolerance_hz) || heard(peaks, tones[1], tolerance_hz);
}
}  // namespace

std::optional<Reply> decode_reply(const TonePlan& plan, std::span<const Peak> peaks,
                                  double tolerance_hz) {
  const bool ack = all_heard(peaks, plan.ack_hz, tolerance_hz);
  const bool nack = all_heard(peaks, plan.nack_hz, tolerance_hz);
  if (ack && !any_heard(peaks, plan.nack_hz, tolerance_hz)) return Reply::Ack;
  if (nack && !any_heard(peaks, plan.ack_hz, tolerance_hz)) return Reply::Nack;
  return std::nullopt;
}

}  // namespace dtmf::signal
