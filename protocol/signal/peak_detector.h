// Signal layer: the loudest peaks of a spectrum inside one side's band-pass.
//
// Seed section 8: the spectrum is band-passed (4–17 kHz on the robot, 1.5–4 kHz on the
// sender), a noise gate drops everything quieter than a set level, and the N loudest peaks
// remain (10 on the robot, 5 on the sender). A peak is a bin louder than both neighbours;
// its frequency and level are refined by a parabola through the three log magnitudes, which
// with a Hann window puts a clean tone within about 1 Hz of its true frequency.
#pragma once

#include <span>
#include <vector>

#include "profile/link_profile.h"

namespace dtmf::signal {

struct Peak {
  double frequency_hz;
  double amplitude;  // sine amplitude, full scale = 1.0
};

class PeakDetector {
 public:
  PeakDetector(const DetectorParams& params, double bin_hz, std::size_t bin_count);

  // The loudest peaks of `magnitudes`, loudest first; valid until the next call.
  std::span<const Peak> detect(std::span<const float> magnitudes);
  // The bins detect() reads: the band-pass and one either side, [first, end).
  std::size_t first_read_bin() const { return first_bin_ - 1; }
  std::size_t end_read_bin() const { return last_bin_ + 2; }

 private:
  std::size_t first_bin_;
  std::size_t last_bin_;
  double bin_hz_;
  float gate_;
  std::size_t peak_count_;
  std::vector<Peak> candidates_;
};

double dbfs(double amplitude);
double amplitude_from_dbfs(double level_dbfs);

}  // namespace dtmf::signal
