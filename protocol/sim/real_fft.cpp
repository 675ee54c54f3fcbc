#include "sim/real_fft.h"

#include <fftw3.h>

#include <algorithm>
#include <mutex>
#include <new>

namespace dtmf::sim {

namespace {

// Before main(): from here on FFTW serialises its own planner, for every caller in the
// process (the signal layer plans under its own lock as well, which stays harmless).
const bool kPlannerThreadSafe = [] {
  fftwf_make_planner_thread_safe();
  return true;
}();

// Plans are made under a lock all the same: the switch above has run only if this file's
// static initialisers ran before the first plan, which a static library does not promise
// for code that plans during static initialisation elsewhere.
std::mutex& plan_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

template <typename T>
T* FftwAllocator<T>::allocate(std::size_t n) {
  void* p = fftwf_malloc(n * sizeof(T));
  if (!p && n > 0) throw std::bad_alloc();
  return static_cast<T*>(p);
}

template <typename T>
void FftwAllocator<T>::deallocate(T* p, std::size_t) noexcept {
  fftwf_free(p);
}

template struct FftwAllocator<float>;
template struct FftwAllocator<std::complex<float>>;

RealFft::RealFft(std::size_t n) : n_(n) {
  (void)kPlannerThreadSafe;
  FftReal real(n);
  FftBins bins(n / 2 + 1);
  auto* complex = reinterpret_cast<fftwf_complex*>(bins.data());
  std::lock_guard lock(plan_mutex());
  forward_plan_ = fftwf_plan_dft_r2c_1d(static_cast<int>(n), real.data(), complex, FFTW_ESTIMATE);
  inverse_plan_ = fftwf_plan_dft_c2r_1d(static_cast<int>(n), complex, real.data(), FFTW_ESTIMATE);
  if (!forward_plan_ || !inverse_plan_) throw std::bad_alloc();
}

RealFft::~RealFft() {
  std::lock_guard lock(plan_mutex());
  fftwf_destroy_plan(static_cast<fftwf_plan>(forward_plan_));
  fftwf_destroy_plan(static_cast<fftwf_plan>(inverse_plan_));
}

void RealFft::forward(const float* in, std::complex<float>* out) const {
  fftwf_execute_dft_r2c(static_cast<fftwf_plan>(forward_plan_), const_cast<float*>(in),
                        reinterpret_cast<fftwf_complex*>(out));
}

void RealFft::inverse(std::complex<float>* in, float* out) const {
  fftwf_execute_dft_c2r(static_cast<fftwf_plan>(inverse_plan_), reinterpret_cast<fftwf_complex*>(in), out);
}

std::size_t fft_size_at_least(std::size_t n) {
  std::size_t best = 1;
  while (best < n) best *= 2;
  for (std::size_t three = 3; three < best; three *= 3) {
    std::size_t candidate = three;
    while (candidate < n) candidate *= 2;
    best = std::min(best, candidate);
  }
  return std::max<std::size_t>(best, 2);
}

std::vector<float> convolve(std::span<const float> a, std::span<const float> b) {
  if (a.empty() || b.empty()) return {};
  const std::size_t length = a.size() + b.size() - 1;
  const RealFft fft(fft_size_at_least(length));
  FftReal x(fft.size(), 0.0f), y(fft.size(), 0.0f);
  std::copy(a.begin(), a.end(), x.begin());
  std::copy(b.begin(), b.end(), y.begin());
  FftBins xs(fft.bins()), ys(fft.bins());
  fft.forward(x.data(), xs.data());
  fft.forward(y.data(), ys.data());
  const float scale = 1.0f / static_cast<float>(fft.size());
  for (std::size_t k = 0; k < xs.size(); ++k) xs[k] *= ys[k] * scale;
  fft.inverse(xs.data(), x.data());
  return std::vector<float>(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(length));
}

}  // namespace dtmf::sim
