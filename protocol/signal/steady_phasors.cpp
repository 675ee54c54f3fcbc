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

// One window's bins, side by side: the state arrays in and out, X(t) in, |residual| out.
// A free function of restrict pointers: inside the member function GCC could not see that
// nothing aliases, and left the loop scalar (6 times slower).
void remove_steady(std::size_t n, float floor_power, float rise_per_window, const float* __restrict now_re,
                   const float* __restrict now_im, float* __restrict steady_re, float* __restrict steady_im,
                   float* __restrict turn_re, float* __restrict turn_im, float* __restrict last_re,
                   float* __restrict last_im, float* __restrict usual_of, float* __restrict last_steady,
                   float* __restrict out) {
  // No branch: each choice is a select or a product with a 0/1 flag (a product by 1 or 0
  // gives the same bits as the branch it replaces), so the bins run four to a SIMD register.
  for (std::size_t i = 0; i < n; ++i) {
    const float x_re = now_re[i], x_im = now_im[i];
    // The steady phasor, turned by a window's turn (unit length: only its angle counts).
    const float turn_size = std::sqrt(turn_re[i] * turn_re[i] + turn_im[i] * turn_im[i]);
    const float u_re = turn_size > 0 ? turn_re[i] / turn_size : 1.0f;
    const float u_im = turn_size > 0 ? turn_im[i] / turn_size : 0.0f;
    const float p_re = steady_re[i] * u_re - steady_im[i] * u_im;
    const float p_im = steady_re[i] * u_im + steady_im[i] * u_re;
    const float r_re = x_re - p_re, r_im = x_im - p_im;
    const float power = r_re * r_re + r_im * r_im;
    const float usual = std::max(usual_of[i], floor_power);
    // Only a steady sound well over the residual is taken off: a bin of noise, or a faint
    // tone partly learnt, reads as it is.
    const float predicted_power = p_re * p_re + p_im * p_im;
    const float left = std::sqrt(power), whole = std::sqrt(x_re * x_re + x_im * x_im);
    out[i] = predicted_power > kTakenOffRatio * usual ? left : whole;
    const float steady = power <= kSteadyRatio * usual ? 1.0f : 0.0f;
    // Learnt from a steady window, carried through one that held something else.
    steady_re[i] = p_re + steady * (kLearnPerWindow * r_re);
    steady_im[i] = p_im + steady * (kLearnPerWindow * r_im);
    // The turn only from two steady windows in a row: the window after a chord still
    // compares with the chord.
    const float turn_learnt = steady * last_steady[i];
    turn_re[i] += turn_learnt * (kTurnPerWindow * (x_re * last_re[i] + x_im * last_im[i] - turn_re[i]));
    turn_im[i] += turn_learnt * (kTurnPerWindow * (x_im * last_re[i] - x_re * last_im[i] - turn_im[i]));
    // A fall at once, so that chords repeated every second cannot ratchet it up to their
    // tones' power (a mean would fall back only a little in each gap).
    usual_of[i] = std::min(power, usual * rise_per_window);
    last_steady[i] = steady;
    last_re[i] = x_re;
    last_im[i] = x_im;
  }
}
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
  for (auto* v : {&steady_re_, &steady_im_, &turn_re_, &turn_im_, &last_re_, &last_im_, &usual_, &last_steady_,
                  &now_re_, &now_im_})
    v->resize(end_bin - first_bin);
  reset();
}

void SteadyPhasors::reset() {
  for (auto* v : {&steady_re_, &steady_im_, &turn_re_, &turn_im_, &last_re_, &last_im_, &last_steady_})
    std::fill(v->begin(), v->end(), 0.0f);
  std::fill(usual_.begin(), usual_.end(), floor_power_);
}

std::span<const float> SteadyPhasors::remove(std::span<const std::complex<float>> phasors) {
  const std::size_t n = std::min(phasors.size(), first_bin_ + usual_.size()) - std::min(phasors.size(), first_bin_);
  const std::complex<float>* x = phasors.data() + first_bin_;
  float* out = residual_.data() + first_bin_;
  if (!enabled_) {
    for (std::size_t i = 0; i < n; ++i) out[i] = std::sqrt(x[i].real() * x[i].real() + x[i].imag() * x[i].imag());
    return residual_;
  }
  // Real and imaginary parts apart first, as plain float arrays.
  for (std::size_t i = 0; i < n; ++i) {
    now_re_[i] = x[i].real();
    now_im_[i] = x[i].imag();
  }
  remove_steady(n, floor_power_, rise_per_window_, now_re_.data(), now_im_.data(), steady_re_.data(), steady_im_.data(),
                turn_re_.data(), turn_im_.data(), last_re_.data(), last_im_.data(), usual_.data(), last_steady_.data(),
                out);
  return residual_;
}

}  // namespace dtmf::signal
