// Physical layer, room helpers: a real-to-complex FFT of one size, with FFTW3 (float).
//
// forward() turns n real samples into n/2 + 1 complex bins; inverse() turns them back into
// n samples scaled by n (FFTW's convention, left to the caller because most callers fold
// the 1/n into a gain they apply anyway). Plans are made once, with FFTW_ESTIMATE (no
// timing runs: a channel is built in milliseconds), and executed with FFTW's new-array
// interface, so the caller's buffers are used in place and nothing is allocated per call.
//
// Thread safety: FFTW's planner is not thread-safe. Loading this module switches on
// fftwf_make_planner_thread_safe() before main() runs, which makes every plan in the
// process (the signal layer's too) safe to make and destroy from any thread.
#pragma once

#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace dtmf::sim {

// std::complex<float> has the layout of fftwf_complex; buffers from this allocator are
// aligned as FFTW's SIMD code wants.
template <typename T>
struct FftwAllocator {
  using value_type = T;
  FftwAllocator() = default;
  template <typename U>
  FftwAllocator(const FftwAllocator<U>&) {}
  T* allocate(std::size_t n);
  void deallocate(T* p, std::size_t) noexcept;
  template <typename U>
  bool operator==(const FftwAllocator<U>&) const {
    return true;
  }
};

using FftReal = std::vector<float, FftwAllocator<float>>;
using FftBins = std::vector<std::complex<float>, FftwAllocator<std::complex<float>>>;

class RealFft {
 public:
  explicit RealFft(std::size_t n);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  std::size_t size() const { return n_; }
  std::size_t bins() const { return n_ / 2 + 1; }

  // `in`: size() samples, `out`: bins() values; both from FftwAllocator.
  void forward(const float* in, std::complex<float>* out) const;
  // `in`: bins() values (overwritten: FFTW's c2r destroys its input), `out`: size() samples.
  void inverse(std::complex<float>* in, float* out) const;

 private:
  std::size_t n_;
  void* forward_plan_;
  void* inverse_plan_;
};

// The smallest size >= n of the form 2^a * 3^b (FFTW is fast for those).
std::size_t fft_size_at_least(std::size_t n);

// Linear convolution of two finite signals (through one FFT of each).
std::vector<float> convolve(std::span<const float> a, std::span<const float> b);

}  // namespace dtmf::sim
