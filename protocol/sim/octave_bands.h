// Physical layer, room helpers: the eight octave bands a room is described in (125 Hz to
// 16 kHz), and a filter bank that splits a signal into them and sums back to the original.
//
// A wall's reflection, a band's decay time: values per band, BandValues. The filter bank is
// zero-phase (a real gain per FFT bin, i.e. a linear-phase filter without its delay): each
// band's gain is 1 within a third of an octave of its centre and crosses over to its
// neighbour's with cos^2 / sin^2 over the third of an octave around the band edge (on a
// log-frequency axis), so the eight gains add up to exactly 1 at every frequency. Why sum
// to 1: an image source whose every band has the same amplitude then comes out as an
// unfiltered impulse (the direct sound stays one clean sample). Why a narrow crossover: a
// band's own values rule most of its octave, so a band that reflects less really decays
// faster (with crossovers an octave wide, a slow neighbour's tail leaked into it and
// dominated its decay). The crossover's ringing (about 20 ms at 177 Hz) is harmless.
// Below 125 Hz the lowest band takes everything, above 16 kHz the highest.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace dtmf::sim {

inline constexpr std::size_t kOctaveBands = 8;
inline constexpr std::array<double, kOctaveBands> kOctaveCentresHz = {125, 250, 500, 1000, 2000, 4000, 8000, 16000};

inline constexpr double kCrossoverOctaves = 1.0 / 3;

using BandValues = std::array<double, kOctaveBands>;

inline BandValues uniform_bands(double value) {
  BandValues v;
  v.fill(value);
  return v;
}

// Gain of band `band` at `frequency_hz` (the eight add up to 1 at every frequency).
double band_weight(std::size_t band, double frequency_hz);

// The analysis filter for measuring a band (band_filtered): the middle half octave of the
// band, flat within a sixth of an octave of its centre. Narrower than the bank's bands so
// that a measurement sees the band's own decay, not a slower neighbour's crossover.
double band_analysis_weight(std::size_t band, double frequency_hz);

// Values given at some frequencies (Hz, value), interpolated on a log-frequency axis to the
// eight centres; constant beyond the first and last. Throws std::invalid_argument if empty.
BandValues bands_from_points(std::span<const std::pair<double, double>> points);

// `signal` filtered to the middle of one band with band_analysis_weight() (same length;
// zero-phase, so the ringing before a sharp event is cut off at the start, not wrapped).
std::vector<float> band_filtered(std::span<const float> signal, std::size_t band, int sample_rate_hz);

// "125 Hz", "16 kHz": for messages.
std::string band_name(std::size_t band);

}  // namespace dtmf::sim
