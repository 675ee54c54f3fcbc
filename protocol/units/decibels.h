// Decibels, one definition for every layer: a level in dB is 10·log10 of a power ratio and
// 20·log10 of an amplitude (field) ratio, so the two conversions must never be mixed up.
// As spandsp's dds/dtmf code does, the call names which one is meant: power (band powers,
// SNR, thresholds on |X|²) or amplitude (sample values, gains applied to samples, |X|).
// Header-only; no layer below it.
#pragma once

#include <cmath>

namespace dtmf::units {

// 10^(db/10): +3 dB is twice the power.
inline double power_ratio_from_db(double db) { return std::pow(10.0, db / 10.0); }
// 10^(db/20): +6 dB is twice the amplitude.
inline double amplitude_ratio_from_db(double db) { return std::pow(10.0, db / 20.0); }
// 10·log10(ratio) for a ratio of powers.
inline double db_from_power_ratio(double ratio) { return 10.0 * std::log10(ratio); }
// 20·log10(ratio) for a ratio of amplitudes.
inline double db_from_amplitude_ratio(double ratio) { return 20.0 * std::log10(ratio); }

}  // namespace dtmf::units
