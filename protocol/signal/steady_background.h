// Signal layer: a per-bin background that learns steady tones, taken off a magnitude spectrum.
//
// A fan, a charger or a motor driver whines on one frequency for minutes; a chord's tone
// lasts under a second. Each bin's background follows a fall of its magnitude at once and
// a rise only at `rise_db_per_s`, so within seconds a whine becomes background while a
// chord's tone stays above it. What is returned is each bin's excess over its background,
// as a magnitude: sqrt(max(0, m^2 - b^2)). The background starts at `floor` (the noise
// gate): a whine present from the start is learnt at the rise rate, as a chord would be if
// the stream began inside one. Allocation-free after construction.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace dtmf::signal {

class SteadyBackground {
 public:
  // `rise_db_per_s` 0 turns the background off: magnitudes pass unchanged.
  SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor);

  std::span<const float> remove(std::span<const float> magnitudes);
  void reset();

 private:
  bool enabled_;
  float rise_per_window_;  // linear magnitude factor
  float floor_;
  std::vector<float> background_;
  std::vector<float> excess_;
};

}  // namespace dtmf::signal
