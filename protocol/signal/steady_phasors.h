// Signal layer: steady tones taken off a complex spectrum, phase and all — the seed
// listener's answer to a whine on the very bin of one of its tones.
//
// A power background (steady_background.h) learns a whine's power, but a chord's tone on the
// same bin adds to the whine as a phasor: |w + t|² lies anywhere between (|w| − |t|)² and
// (|w| + |t|)², so with a whine 6 dB over the tone the power left over the background is
// anything from −3 to +5 tone powers, and the tone is lost about one time in three. A steady
// sine, though, is predictable window by window: between two windows a hop H apart its
// phasor turns by 2π f H / rate, whatever the window shape. So each bin keeps
//   - the turn per window of what it holds, averaged over the windows that held only their
//     steady sound;
//   - its steady phasor, learnt at `kLearnPerWindow` from those windows, and carried forward by
//     the turn through windows that did not (a chord's tone, a click);
// and hands on |X − predicted steady phasor| where that phasor stands well over the bin's
// usual residual: a whine leaves nothing, a tone on its bin leaves the tone; elsewhere |X|. What counts as holding only
// the steady sound: a residual power within `kSteadyRatio` of the bin's usual residual, which follows a fall at once
// and a rise only at `rise_db_per_s` (as steady_background.h's background does): a whine that appears is learnt within
// seconds, a chord of 0.8 s lifts it by 8 dB at most and is never learnt. A bin without a steady tone learns the mean
// of its noise, near zero. Allocation-free after construction.
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <vector>

namespace dtmf::signal {

class SteadyPhasors {
 public:
  // Tracks bins [first_bin, end_bin) of spectra of `bins` bins (a listener's band: the rest
  // read 0). `floor`: a magnitude under which nothing counts as rising (the noise gate).
  SteadyPhasors(std::size_t bins, std::size_t first_bin, std::size_t end_bin, double rise_db_per_s,
                double windows_per_s, float floor);

  // Each bin's magnitude once its steady tone is taken off (valid until the next call).
  std::span<const float> remove(std::span<const std::complex<float>> phasors);
  void reset();

 private:
  // One array per quantity (plain floats, not std::complex, whose operators check for
  // infinities on every product), so that the bins run side by side in SIMD lanes.
  bool enabled_;
  std::size_t first_bin_;
  float rise_per_window_;  // power factor
  float floor_power_;
  std::vector<float> steady_re_, steady_im_;  // the steady sound's phasor in the window before
  std::vector<float> turn_re_, turn_im_;      // mean of X(t) conj(X(t - 1)) over steady windows
  std::vector<float> last_re_, last_im_;      // X(t - 1)
  std::vector<float> usual_;                  // the residual's usual power
  std::vector<float> last_steady_;            // 1 where the window before held only its steady sound
  std::vector<float> now_re_, now_im_;        // X(t), scratch
  std::vector<float> residual_;
};

}  // namespace dtmf::signal
