// Signal layer: a frame candidate that did not decode, read again over each chord's whole
// steady part — the fast frame listener's last hypothesis (hop_listener.h).
//
// A chord holds its tones for W + hop samples (between its fades), but the one grid window
// wholly inside it reads W of them: 1920 of 2412, 80 % of each tone's energy. Read over all
// W + hop samples, a tone stands 10 log10((W + hop) / W) = 1.0 dB higher over the noise in
// its bin, and at -12 dB SNR that halves the tones misread (32-ary noncoherent detection:
// 12.8 % -> 6.0 %). Two things the grid knows only roughly are searched for:
//   - where the chords' steady parts begin: the grid window lies somewhere inside its chord,
//     so over that hop, for the most power in the bands' strongest half bins, in steps of four
//     `reread_step_samples` and then of one around the best (all chords summed into one
//     2 W-point transform: their bands are disjoint);
//   - the frequency offset (clocks, Doppler): over the whole ±max_offset_ppm, in steps of
//     250 ppm and then of 50 around the best, for the most power in the bands' strongest
//     tones; none unless another reads 0.2 dB more. Over 50 ms a tone read 6 Hz off loses
//     1.5 dB, more than the re-read gains, and the offset tracked from earlier frames scatters
//     by several hundred ppm at -12 dB; trying an offset costs no transform, only reads.
//
// How: the W + hop samples, zero-padded to 4 W, go through one FFT, so every grid bin (a tone
// spacing) is every fourth bin and an offset moves a tone by quarter bins; grid bin k at an
// offset is read at 4 k (1 + offset), at most 3.1 Hz from the tone (0.4 dB lost over 50 ms).
// Powers are scaled by (W / (W + hop))^2 to the grid window's units: a steady tone reads the
// same in both (so the background learnt on the grid comes off as it is), and the noise 1.0 dB
// lower. The samples come from a history of the stream's latest samples, pushed every hop.
// Planned with FFTW_ESTIMATE: it runs only on candidates that failed, and measuring a
// 7680-point plan would cost every receiver's start-up more than all its re-reads.
// Nothing is allocated after construction.
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_power.h"

namespace dtmf::signal {

// One chord's bins as the grid's windows hold them: raw power, and excess over the background.
struct ChordPowers {
  std::vector<float> power;
  std::vector<float> excess;
};

// What a re-read found besides the bins: the offset it read them at, and where the first
// chord's steady part began.
struct WholeChordFit {
  int offset_ppm = 0;
  long long steady_start_age = 0;  // samples before the newest pushed
};

class WholeChordReader {
 public:
  // The grid's bins [lo_bin, lo_bin + bins), as the frame listener analyses them, for frames
  // of up to `max_chords` chords.
  WholeChordReader(const HopPlan& hops, int lo_bin, int bins, int max_chords);

  // Appends the stream's newest samples to the history.
  void push(std::span<const float> samples);

  // A frame of `chords` chords whose grid window inside its last chord ended `age` samples
  // before the newest pushed. Finds its steady start and offset, then writes out[c + 1] for
  // chord c, every grid bin read where the offset moves it, and out[0] from `before`: the grid
  // window's powers a chord before the frame's first grid window (onsets are measured against
  // it, as the grid's readings are: a tone that was there before the frame holds its level
  // wherever the re-read finds the chord to start). `background` is the grid's steady
  // background per bin. Returns the offset and the steady start found, or nothing when the
  // history no longer holds the frame.
  std::optional<WholeChordFit> read(long long age, int chords, std::span<const float> background,
                                    std::span<const float> before, std::span<ChordPowers> out);

  // How far back the history reaches, in samples.
  long long history_samples() const { return static_cast<long long>(history_.size()); }

 private:
  // Adds the steady part starting at sample `start` of the stream to the front of `padded`.
  void add_steady(long long start, std::span<float> padded) const;
  // The reading FFT's powers of the steady part starting at sample `start`.
  void transform(long long start, std::span<float> power);
  // The reading FFT's bin for grid bin `bin` at `step` = 4 (1 + offset) quarter bins a bin.
  std::size_t padded_bin(int bin, float step) const;
  // Grid bin `bin` at the offset `scale` (1 + offset) from the reading FFT's powers, in grid units.
  float grid_power(std::span<const float> power, int bin, double scale) const;
  // The sum over a chord's bands of their strongest tone's power at the offset.
  float strongest_tones(std::span<const float> power, int chord, double scale) const;
  // The start search's measure: the chords' bands' strongest half bins, steady parts from `start`.
  float start_score(long long start, int chords);

  const HopPlan& hops_;
  int lo_bin_;
  int bins_;
  int steady_samples_;  // W + hop
  std::size_t first_padded_bin_;
  std::size_t first_search_bin_;
  int search_margin_bins_;      // either side of a band, for tones the largest offset moves
  float unit_;                  // (W / (W + hop))^2
  BinPower fft_;                // 4 W points: the readings
  BinPower search_fft_;         // 2 W points: the start search
  std::vector<float> history_;  // a ring: the stream's sample i at i % size
  std::size_t written_ = 0;     // samples pushed so far
  std::vector<float> padded_;   // 4 W samples: a steady part, then zeros
  std::vector<float> search_padded_;
  std::vector<float> search_power_;
  std::vector<std::vector<float>> chord_power_;  // a frame's chords at the start found
};

}  // namespace dtmf::signal
