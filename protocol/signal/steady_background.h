// Signal layer: a per-bin background that learns steady tones, taken off a spectrum. The one
// copy for every listener: the seed's chord listener (magnitudes) and the fast profile's
// frame and reply listeners (powers).
//
// A fan, a charger or a motor driver whines on one frequency for minutes; a chord's tone
// lasts under a second. Each bin's background power follows a fall of the bin's power at
// once and a rise only at `rise_db_per_s`, so within seconds a whine becomes background
// while a chord's tone stays above it. What is taken off is that power: the excess is
// p − b, or as a magnitude sqrt(max(0, m² − b)). Magnitude spectra start at `floor` (the
// noise gate) and never rise from below it: a whine present from the start is learnt at the
// rise rate, as a chord would be if the stream began inside one. Power spectra start at
// their first window (the stream is taken to begin in steady sound). `rise_db_per_s` 0
// turns the background off. Allocation-free after construction.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace dtmf::signal {

class SteadyBackground {
 public:
  // Magnitude spectra (|X|): remove(). Starts at `floor`, a magnitude.
  SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor);
  // Power spectra (|X|²): remove_power(). Starts at the first window's power.
  static SteadyBackground for_power(std::size_t bins, double rise_db_per_s, double windows_per_s);

  // Each bin's excess magnitude over its background (valid until the next call).
  std::span<const float> remove(std::span<const float> magnitudes);
  // Writes each bin's excess power over its background to `excess` (as many as `powers`).
  void remove_power(std::span<const float> powers, std::span<float> excess);
  // Each bin's background power now.
  std::span<const float> background_power() const { return background_; }
  void reset();

 private:
  SteadyBackground(std::size_t bins, double rise_db_per_s, double windows_per_s, float floor_power, float start_power);
  float learn(std::size_t bin, float power);  // the bin's new background power

  bool enabled_;
  float rise_per_window_;  // power factor
  float floor_power_;
  float start_power_;
  std::vector<float> background_;  // power
  std::vector<float> excess_;      // remove()'s magnitudes
};

}  // namespace dtmf::signal
