// Signal layer, part 8: tone bands read off the bins of a rectangular analysis window
// (the fast profile's detector; the seed's is spectrum + peak_detector + chord_decoder).
//
// Tones sit exactly on bins (frequency = bin * rate / window), so a window lying wholly
// inside a chord holds each tone in one bin with no leakage into its neighbours, and a
// rectangular window keeps all of the tone's energy (a Hann window would lose 1.8 dB of
// signal-to-noise ratio). For each band of `tones_per_band` bins it reports the strongest
// bin (the symbol), the runner-up, and whether the band sounds: the best bin stands
// presence_db above the band's floor — the mean of its other bins, measured afresh in every
// window, so the floor follows the noise band by band — and dominance_db above the runner-up,
// as a DTMF receiver demands of its strongest tone. Powers are |X|^2 of the raw FFT; only
// ratios are used. Nothing is allocated per window.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

struct fftwf_plan_s;

namespace dtmf::signal {

struct BandReading {
  std::uint8_t symbol = 0;     // tone index of the best bin
  std::uint8_t runner_up = 0;  // tone index of the second-best bin
  float best = 0;
  float second = 0;
  float floor = 0;
  bool present = false;
  // How sure the symbol is: best over runner-up, as a power ratio (>= 1).
  float certainty() const { return second > 0 ? best / second : 1e9f; }
};

class BinBands {
 public:
  BinBands(int window_samples, std::span<const int> band_first_bin, int tones_per_band, double presence_db,
           double dominance_db);
  ~BinBands();
  BinBands(const BinBands&) = delete;
  BinBands& operator=(const BinBands&) = delete;

  // Analyses `window` (window_samples long) and returns one reading per band.
  std::span<const BandReading> analyze(std::span<const float> window) { return analyze(window, powers_); }
  // The same, with the powers written to `powers` (bands() x tones_per_band) instead of
  // powers(), for a caller that keeps them (BinFrameListener: no copy per window).
  std::span<const BandReading> analyze(std::span<const float> window, std::span<float> powers);

  // Powers of the latest window analysed without a `powers` of its own, band after band,
  // tones_per_band each.
  std::span<const float> powers() const { return powers_; }
  int bands() const { return static_cast<int>(first_bin_.size()); }
  int tones_per_band() const { return tones_; }

 private:
  int window_samples_;
  std::vector<int> first_bin_;
  int tones_;
  float presence_ratio_;
  float dominance_ratio_;
  float* input_;
  void* output_;
  fftwf_plan_s* plan_;
  std::vector<float> powers_;
  std::vector<BandReading> readings_;
};

}  // namespace dtmf::signal
