// Signal layer: chords as audio.
//
// Every tone of a chord has the plan's amplitude and starts at phase 0; the chord fades in
// and out over `edge_ms` with a raised-cosine (Hann) ramp, which keeps the switching
// splatter 40 dB under the chord in the other bands (a hard edge clicks across them all).
#pragma once

#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/tone_plan.h"

namespace dtmf::signal {

// Adds (mixes) a chord of `tones_hz` lasting `out.size()` samples into `out`.
void add_chord(std::span<float> out, std::span<const double> tones_hz, double amplitude, double edge_ms,
               int sample_rate_hz);

// A fresh buffer holding one chord of `duration_ms`.
std::vector<float> synthesize_chord(const LinkProfile& profile, std::span<const double> tones_hz, double duration_ms);

// The command chord of `frame` with the profile's chord length.
std::vector<float> synthesize_frame(const LinkProfile& profile, std::uint16_t frame);

// The ACK or NACK chord with the profile's reply length.
std::vector<float> synthesize_reply(const LinkProfile& profile, Reply reply);

}  // namespace dtmf::signal
