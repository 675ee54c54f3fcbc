// Signal layer: the magnitude spectrum of one analysis window, with FFTW3.
//
// A Hann window (sidelobes at -31 dB, so a loud tone does not bury its neighbours a few
// bins away) is applied, a real-to-complex FFT is run with a plan made once per analyser,
// and each bin's magnitude is scaled to the amplitude of the sine that would produce it
// (a full-scale sine reads 1.0, i.e. 0 dBFS). analyze_phasors() keeps each bin's phase too,
// in the same scale. Nothing is allocated per window.
#pragma once

#include <complex>
#include <mutex>
#include <span>
#include <vector>

struct fftwf_plan_s;

namespace dtmf::signal {

// FFTW's planner is not thread-safe (executing a finished plan is): every plan is made and
// destroyed under this lock.
std::mutex& planner_mutex();

class SpectrumAnalyzer {
 public:
  SpectrumAnalyzer(int fft_size, int sample_rate_hz);
  ~SpectrumAnalyzer();
  SpectrumAnalyzer(const SpectrumAnalyzer&) = delete;
  SpectrumAnalyzer& operator=(const SpectrumAnalyzer&) = delete;

  // `window` must hold fft_size() samples; returns fft_size()/2 + 1 sine amplitudes,
  // valid until the next call.
  std::span<const float> analyze(std::span<const float> window);
  // The same bins as complex amplitudes (|phasor| is analyze()'s magnitude), valid until
  // the next call.
  std::span<const std::complex<float>> analyze_phasors(std::span<const float> window);

  int fft_size() const { return fft_size_; }
  double bin_hz() const { return static_cast<double>(sample_rate_hz_) / fft_size_; }

 private:
  int fft_size_;
  int sample_rate_hz_;
  std::vector<float> window_;  // Hann coefficients
  float amplitude_scale_;      // 2 / sum(window)
  float* input_;               // FFTW-aligned buffers
  void* output_;
  fftwf_plan_s* plan_;
  std::vector<float> magnitudes_;
  std::vector<std::complex<float>> phasors_;

  void transform(std::span<const float> window);
};

}  // namespace dtmf::signal
