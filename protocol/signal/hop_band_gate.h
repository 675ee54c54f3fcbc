// Signal layer: the fast listener's first look at a window — each band's score, and the gate
// that says whether the windows of a frame shape are worth reading.
//
// A band's score is its best bin's excess over the steady background (a whine is background,
// not excess) against the mean raw power of its other bins. The gate counts a chord's bands
// that score `gate_db` or more (counted, not summed: two loud tones, a seed chord or a
// whistle, must not carry a chord whose other bands hold nothing) and needs `gate_bands` of
// eight in every chord: one chord's bands loud and the next one's silent is a frame's edge,
// or the next frame's first chord. A noise band scores 6.2 dB on average (1.5 dB spread), a
// frame's at -10 dB SNR about 12. Short of that, but with `reread_gate_bands` in every chord
// and half of all the bands, a window is only worth a whole-chord re-read: at -12 dB a frame's
// weaker chord misses the gate by a band in 1 % of frames, and the grid's readings of such a
// window seldom decode. Pure: no state but the plan's thresholds.
#pragma once

#include <span>

#include "profile/link_profile.h"
#include "signal/hop_window_history.h"

namespace dtmf::signal {

class HopBandGate {
 public:
  enum class Verdict { Closed, RereadOnly, Open };

  // lo_bin: the spectrum bin the windows' power and excess start at.
  HopBandGate(const HopPlan& plan, int lo_bin);

  // Fills `window.band_score` from its power and excess.
  void score(HopWindow& window) const;
  // chord_windows[c]: the window inside chord c of a frame (its band set c % 2 is judged).
  Verdict judge(std::span<const HopWindow* const> chord_windows) const;

 private:
  const HopPlan& plan_;
  int lo_bin_;
  float gate_ratio_;
};

}  // namespace dtmf::signal
