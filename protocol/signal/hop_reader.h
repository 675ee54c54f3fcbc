// Signal layer: how the fast listener reads a candidate window (one job of hop_listener.h).
//
//   - read(): each band's tone at an offset hypothesis's shifted bins — its symbol, its
//     certainty over the runner-up, whether it stands `presence_db` over the band's median
//     power and rose `onset_db` since the window a chord earlier (a reverberant tail, or any
//     steady sound, decays or holds; a chord's tone starts), and its peak to a fraction of a bin;
//   - blind_offset_ppm(): the offset a window's own peaks show (tones sit on bins, so the
//     offset that brings most peaks nearest whole bins);
//   - first_chord_start_sample(): where the frame began — the earliest rise of its first
//     chord's heard tones across the windows (chord_onset.h): a clean frame decodes from
//     windows astride its chords' starts, hops before the ones wholly inside them.
// No state between calls but scratch space: allocation-free after construction.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/hop_candidate.h"
#include "signal/hop_window_history.h"

namespace dtmf::signal {

class HopReader {
 public:
  // lo_bin: the spectrum bin the windows' power and excess start at; history_windows: how many
  // windows the listener keeps (the most a start is searched over).
  HopReader(const LinkProfile& profile, int lo_bin, std::size_t history_windows);

  // Readings of a frame of `chords` from windows[c + 1] for chord c (windows[0]: a chord
  // before the frame, the floor its tones must rise from), taken at the bins of `offset_ppm`.
  HopCandidate read(int chords, int offset_ppm, std::span<const ChordPowers* const> windows) const;
  // The offset of the frame whose chord c lies in chord_windows[c], from its peaks alone.
  int blind_offset_ppm(std::span<const HopWindow* const> chord_windows) const;
  // Where the first chord of `c` began, in samples since the first fed (the newest window of
  // `history` ends at `samples_fed`), or nothing when fewer than half of its tones rose clearly
  // where the grid could have read the frame.
  std::optional<long long> first_chord_start_sample(const HopCandidate& c, const HopWindowHistory& history,
                                                    long long samples_fed) const;

  // Room either side of a band for tones moved by a frequency offset, and for a guard bin.
  static constexpr int kMarginBins = 4;

 private:
  const HopPlan& plan_;
  int lo_bin_;
  int hop_;
  int hops_per_chord_;
  float presence_ratio_;
  float onset_ratio_;
  mutable std::vector<float> scratch_;          // a band's tones' excess (readings)
  mutable std::vector<float> floor_;            // ... and their raw power (the floor)
  mutable std::vector<float> onset_amplitude_;  // a first-chord tone, window by window (start)
};

}  // namespace dtmf::signal
