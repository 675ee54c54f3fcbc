#include "signal/spectrum.h"

#include <fftw3.h>

#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace dtmf::signal {

std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

SpectrumAnalyzer::SpectrumAnalyzer(int fft_size, int sample_rate_hz)
    : fft_size_(fft_size), sample_rate_hz_(sample_rate_hz), window_(static_cast<std::size_t>(fft_size)) {
  if (fft_size < 16 || (fft_size & (fft_size - 1)) != 0) {
    throw std::invalid_argument("FFT size must be a power of two of at least 16, got " + std::to_string(fft_size));
  }
  double sum = 0;
  for (int i = 0; i < fft_size; ++i) {
    window_[static_cast<std::size_t>(i)] =
        static_cast<float>(0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / fft_size));
    sum += window_[static_cast<std::size_t>(i)];
  }
  amplitude_scale_ = static_cast<float>(2.0 / sum);
  magnitudes_.resize(static_cast<std::size_t>(fft_size / 2 + 1));
  phasors_.resize(static_cast<std::size_t>(fft_size / 2 + 1));

  std::lock_guard lock(planner_mutex());
  input_ = fftwf_alloc_real(static_cast<std::size_t>(fft_size));
  output_ = fftwf_alloc_complex(static_cast<std::size_t>(fft_size / 2 + 1));
  plan_ = fftwf_plan_dft_r2c_1d(fft_size, input_, static_cast<fftwf_complex*>(output_), FFTW_ESTIMATE);
}

SpectrumAnalyzer::~SpectrumAnalyzer() {
  std::lock_guard lock(planner_mutex());
  fftwf_destroy_plan(plan_);
  fftwf_free(input_);
  fftwf_free(output_);
}

void SpectrumAnalyzer::transform(std::span<const float> window) {
  if (window.size() != static_cast<std::size_t>(fft_size_)) {
    throw std::invalid_argument("analysis window must hold " + std::to_string(fft_size_) + " samples, got " +
                                std::to_string(window.size()));
  }
  for (int i = 0; i < fft_size_; ++i)
    input_[i] = window[static_cast<std::size_t>(i)] * window_[static_cast<std::size_t>(i)];
  fftwf_execute(plan_);
}

std::span<const float> SpectrumAnalyzer::analyze(std::span<const float> window) {
  transform(window);
  const auto* bins = static_cast<const fftwf_complex*>(output_);
  for (std::size_t k = 0; k < magnitudes_.size(); ++k) {
    magnitudes_[k] = std::hypot(bins[k][0], bins[k][1]) * amplitude_scale_;
  }
  return magnitudes_;
}

std::span<const std::complex<float>> SpectrumAnalyzer::analyze_phasors(std::span<const float> window) {
  transform(window);
  const auto* bins = static_cast<const fftwf_complex*>(output_);
  for (std::size_t k = 0; k < phasors_.size(); ++k) {
    phasors_[k] = std::complex<float>(bins[k][0], bins[k][1]) * amplitude_scale_;
  }
  return phasors_;
}

}  // namespace dtmf::signal
