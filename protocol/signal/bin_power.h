// Signal layer: the power of a range of bins of an analysis window.
//
// FFTW (single precision, r2c, planned once) transforms the window. Rectangular (as it is):
// the fast profile's frame tones sit on bin centres, so a window lying wholly inside a chord
// holds each tone in one bin with nothing of it in the others, and a rectangular window keeps
// all of a tone's energy (a Hann window would lose 1.8 dB of signal-to-noise ratio). Hann:
// for the replies, which must be read beside frames 20 dB louder a few hundred hertz above
// them; a tone on a bin centre then spreads over three bins and nothing of it reaches the
// bins beyond. Powers are |X|^2 of the FFT; only ratios are used. Nothing is allocated per
// window.
#pragma once

#include <span>
#include <vector>

struct fftwf_plan_s;

namespace dtmf::signal {

enum class Weighting { Rectangular, Hann };
// Measured: the fastest plan FFTW finds (kept in its wisdom, fft_wisdom.h), for windows read
// every hop. Estimated: planned at once, for transforms run only now and then.
enum class Planning { Measured, Estimated };

class BinPower {
 public:
  // Bins [first_bin, first_bin + bins) of a window of `window_samples`.
  BinPower(int window_samples, int first_bin, int bins, Weighting weighting = Weighting::Rectangular,
           Planning planning = Planning::Measured);
  ~BinPower();
  BinPower(const BinPower&) = delete;
  BinPower& operator=(const BinPower&) = delete;

  // Writes the powers of the bins to `out` (bins() values): out[i] is bin first_bin() + i.
  void analyze(std::span<const float> window, std::span<float> out);
  int first_bin() const { return first_bin_; }
  int bins() const { return bins_; }

 private:
  int window_samples_;
  int first_bin_;
  int bins_;
  std::vector<float> weights_;  // empty: rectangular
  float* input_;
  void* output_;
  fftwf_plan_s* plan_;
};

}  // namespace dtmf::signal
