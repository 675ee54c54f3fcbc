#include "signal/tone_plan.h"

#include <cmath>

namespace dtmf::signal {

Chord chord_for(const TonePlan& plan, std::uint16_t frame) {
  Chord chord{};
  for (int band = 0; band < 4; ++band) {
    const int nibble = (frame >> (12 - 4 * band)) & 0xF;
    chord[static_cast<std::size_t>(band)] = plan.band_low_hz[static_cast<std::size_t>(band)] + nibble * plan.step_hz;
  }
  return chord;
}

std::uint16_t frame_for(const TonePlan& plan, const Chord& chord) {
  std::uint16_t frame = 0;
  for (int band = 0; band < 4; ++band) {
    const auto b = static_cast<std::size_t>(band);
    long nibble = std::lround((chord[b] - plan.band_low_hz[b]) / plan.step_hz);
    if (nibble < 0) nibble = 0;
    if (nibble > plan.tones_per_band - 1) nibble = plan.tones_per_band - 1;
    frame = static_cast<std::uint16_t>(frame | (nibble << (12 - 4 * band)));
  }
  return frame;
}

std::optional<PlanTone> match_band_tone(const TonePlan& plan, int band, double frequency_hz, double tolerance_hz) {
  const double offset = frequency_hz - plan.band_low_hz[static_cast<std::size_t>(band)];
  const long nibble = std::lround(offset / plan.step_hz);
  if (nibble < 0 || nibble >= plan.tones_per_band) return std::nullopt;
  if (std::abs(offset - nibble * plan.step_hz) > tolerance_hz) return std::nullopt;
  return PlanTone{band, static_cast<int>(nibble)};
}

std::optional<PlanTone> match_plan_tone(const TonePlan& plan, double frequency_hz, double tolerance_hz) {
  for (int band = 0; band < 4; ++band) {
    if (const auto tone = match_band_tone(plan, band, frequency_hz, tolerance_hz)) return tone;
  }
  return std::nullopt;
}

unsigned bands_within_reach(const TonePlan& plan, double low_hz, double high_hz, double tolerance_hz) {
  unsigned bands = 0;
  for (int band = 0; band < 4; ++band) {
    const double lowest = plan.band_low_hz[static_cast<std::size_t>(band)];
    const double highest = lowest + (plan.tones_per_band - 1) * plan.step_hz;
    if (high_hz + tolerance_hz >= lowest && low_hz - tolerance_hz <= highest) bands |= 1u << band;
  }
  return bands;
}

const std::array<double, 2>& reply_tones(const TonePlan& plan, Reply reply) {
  return reply == Reply::Ack ? plan.ack_hz : plan.nack_hz;
}

}  // namespace dtmf::signal
