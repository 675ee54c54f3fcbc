// Signal layer: the fast listener's recent analysis windows — each one's raw bin power, its
// excess over the steady background and its bands' scores — kept for as long as a frame of
// the most chords, the window a chord before it and a second look's delay need them.
// A ring: allocation-free after construction; the windows before the first read all zero
// (the stream is taken to be preceded by silence).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "profile/link_profile.h"
#include "signal/whole_chord_reader.h"

namespace dtmf::signal {

struct HopWindow : ChordPowers {
  // The band's best excess over its mean power, band set s, band b at [s * 8 + b].
  std::array<float, 2 * HopPlan::kBandsPerChord> band_score{};
};

class HopWindowHistory {
 public:
  HopWindowHistory(std::size_t windows, std::size_t bins) : ring_(windows) {
    for (HopWindow& w : ring_) {
      w.power.assign(bins, 0.0f);
      w.excess.assign(bins, 0.0f);
    }
  }
  // The oldest window's place, now the newest's, to be filled.
  HopWindow& advance() {
    newest_ = (newest_ + 1) % ring_.size();
    return ring_[newest_];
  }
  // The window `age` windows before the newest (0: the newest); age < size().
  const HopWindow& aged(std::size_t age) const { return ring_[(newest_ + ring_.size() - age) % ring_.size()]; }
  std::size_t size() const { return ring_.size(); }

 private:
  std::vector<HopWindow> ring_;
  std::size_t newest_ = 0;
};

}  // namespace dtmf::signal
