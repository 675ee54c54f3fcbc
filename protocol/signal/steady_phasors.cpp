#include "signal/steady_phasors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "units/decibels.h"

namespace dtmf::signal {

namespace {
// The steady phasor moves a tenth of the way to each steady window's value: learnt within a
// second at 20 windows a second; a bin of plain noise keeps a mean about a quarter of its
// noise's amplitude (never taken off: kTakenOffRatio).
constexpr float kLearnPerWindow = 0.1f;
// The turn per window is averaged over about 20 steady windows: a whine 40 dB over the
// noise gets it right to a thousandth of a radian, so a whine twice a tone's amplitude,
// carried forward through a 0.8 s chord (16 windows), leaves under a tenth of the tone.
constexpr float kTurnPerWindow = 0.05f;
// A window holds only its steady sound while its residual power is at most 6 dB over the
// usual: noise exceeds that now and then (such a window teaches nothing), a chord's tone
// over a learnt whine always does.
constexpr float kSteadyRatio = 4.0f;
// A steady phasor is taken off only when its power is 10 dB over the usual residual: a bin of
// noise learns a mean of about a third of its noise, and a tone at low SNR that passes for
// steady now and then is learnt a little; neither may be taken off the tone that follows.
constexpr float kTakenOffRatio = 10.0f;
}  // namespace

SteadyPhasors::SteadyPhasors(std::size_t bins, std::size_t first_bin, std::size_t end_bin, double rise_db_per_s,
                             double windows_per_s, float floor)
    : enabled_(rise_db_per_s > 0),
      first_bin_(first_bin),
      rise_per_window_(static_cast<float>(units::power_ratio_from_db(rise_db_per_s / windows_per_s))),
      floor_power_(floor * floor),
      residual_(bins, 0.0f) {
  if (rise_db_per_s < 0 || windows_per_s <= 0) {
    throw std::invalid_argument("steady phasors need a rise of 0 dB/s or more and windows per second over 0, got " +
                                std::to_string(rise_db_per_s) + " dB/s and " + std::to_string(windows_per_s));
  }
  if (first_bin > end_bin || end_bin > bins) {
    throw std::invalid_argument("steady phasors: bins [" + std::to_string(first_bin) + ", " + std::to_string(end_bin) +
                                ") do not lie within a spectrum of " + std::to_string(bins) + " bins");
  }
  bins_.resize(end_bin - first_bin);
  reset();
}

void SteadyPhasors::reset() {
  for (Bin& b : bins_) b = Bin{0, 0, 0, 0, 0, 0, floor_power_, false};
}

std::span<const float> SteadyPhasors::remove(std::span<const std::complex<float>> phasors) {
  const std::size_t end = std::min(phasors.size(), first_bin_ + bins_.size());
  for (std::size_t k = first_bin_; k < end; ++k) {
    const float x_re = phasors[k].real(), x_im = phasors[k].imag();
    if (!enabled_) {
      residual_[k] = std::sqrt(x_re * x_re + x_im * x_im);
      continue;
    }
    Bin& b = bins_[k - first_bin_];
    // The steady phasor, turned by a window's turn (unit length: only its angle counts).
    const float turn_size = std::sqrt(b.turn_re * b.turn_re + b.turn_im * b.turn_im);
    const float u_re = turn_size > 0 ? b.turn_re / turn_size : 1.0f;
    const float u_im = turn_size > 0 ? b.turn_im / turn_size : 0.0f;
    const float p_re = b.steady_re * u_re - b.steady_im * u_im;
    const float p_im = b.steady_re * u_im + b.steady_im * u_re;
    const float r_re = x_re - p_re, r_im = x_im - p_im;
    const float power = r_re * r_re + r_im * r_im;
    const float usual = std::max(b.usual, floor_power_);
    // Only a steady sound well over the residual is taken off: a bin of noise, or a faint
    // tone partly learnt, reads as it is.
    const float predicted_power = p_re * p_re + p_im * p_im;
    residual_[k] = predicted_power > kTakenOffRatio * usual ? std::sqrt(power) : std::sqrt(x_re * x_re + x_im * x_im);
    const bool steady = power <= kSteadyRatio * usual;
    if (steady) {
      b.steady_re = p_re + kLearnPerWindow * r_re;
      b.steady_im = p_im + kLearnPerWindow * r_im;
      // The turn only from two steady windows in a row: the window after a chord still
      // compares with the chord.
      if (b.last_steady) {
        b.turn_re += kTurnPerWindow * (x_re * b.last_re + x_im * b.last_im - b.turn_re);
        b.turn_im += kTurnPerWindow * (x_im * b.last_re - x_re * b.last_im - b.turn_im);
      }
    } else {
      b.steady_re = p_re;  // carried through the window that held something else
      b.steady_im = p_im;
    }
    // A fall at once, so that chords repeated every second cannot ratchet it up to their
    // tones' power (a mean would fall back only a little in each gap).
    b.usual = std::min(power, usual * rise_per_window_);
    b.last_steady = steady;
    b.last_re = x_re;
    b.last_im = x_im;
  }
  return residual_;
}

}  // namespace dtmf::signal
