// Physical layer, room helpers: how fast an impulse response dies away.
//
// The reverberation time is measured as ISO 3382 does: Schroeder's backward integration
// of the squared response gives the energy decay curve (EDC, in dB below the total), a
// least-squares line is fitted to it between -5 and -25 dB (T20), and the line is
// extrapolated to 60 dB. Broadband figures are of the whole response as it is (the way the
// measured rooms' figures in bench/rirs/README.md were taken); per-band figures filter it
// to the middle half octave of one band first (octave_bands.h: band_analysis_weight).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "sim/octave_bands.h"

namespace dtmf::sim {

// EDC(n) = 10 log10(sum_{m >= n} h[m]^2 / sum_m h[m]^2), dB (0 at the start, falling).
std::vector<double> energy_decay_curve_db(std::span<const float> response);

// T20 extrapolated to 60 dB, seconds; nothing when the curve never falls 25 dB.
std::optional<double> rt60_t20_s(std::span<const float> response, int sample_rate_hz);

// The same in each octave band (a band whose response never falls 25 dB has none).
std::array<std::optional<double>, kOctaveBands> band_rt60_t20_s(std::span<const float> response, int sample_rate_hz);

// The first sample at which the EDC has fallen `drop_db`, or the length if it never does.
std::size_t decay_point(std::span<const float> response, double drop_db);

// Direct-to-reverberant ratio, dB: energy within `direct_window_s` of the largest peak
// against all that comes after it.
double direct_to_reverberant_db(std::span<const float> response, int sample_rate_hz, double direct_window_s = 0.0025);

}  // namespace dtmf::sim
