// Signal layer: the tone plan — which frequencies carry which bits.
//
// A 16-bit frame becomes a chord of four tones, one per band: nibble b (most significant
// first; band 4 carries the CRC) with value v sounds at band_low_hz[b] + v * step_hz. The
// reverse takes detected peak frequencies and reads each back to (band, nibble) when it lies
// within the detector's tolerance of a plan tone. ACK and NACK are two-tone chords.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "profile/link_profile.h"

namespace dtmf::signal {

using Chord = std::array<double, 4>;  // Hz, band 1 first

struct PlanTone {
  int band;    // 0..3
  int nibble;  // 0..15
};

enum class Reply { Ack, Nack };

// The four tones of `frame`.
Chord chord_for(const TonePlan& plan, std::uint16_t frame);
// The frame whose tones are `chord` (each rounded to the nearest plan tone of its band).
std::uint16_t frame_for(const TonePlan& plan, const Chord& chord);
// The plan tone within `tolerance_hz` of `frequency_hz`, if any: the first band's that has one.
std::optional<PlanTone> match_plan_tone(const TonePlan& plan, double frequency_hz, double tolerance_hz);
// The same in band `band` (0..3) alone.
std::optional<PlanTone> match_band_tone(const TonePlan& plan, int band, double frequency_hz, double tolerance_hz);
// Bit b set for each band b whose tones' span, widened by `tolerance_hz`, meets [low_hz,
// high_hz]: a superset of the bands whose tones match some frequency in that range.
unsigned bands_within_reach(const TonePlan& plan, double low_hz, double high_hz, double tolerance_hz);
// The two tones of an ACK or NACK.
const std::array<double, 2>& reply_tones(const TonePlan& plan, Reply reply);

}  // namespace dtmf::signal
