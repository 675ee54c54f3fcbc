// Physical layer: steady tonal interferers at the microphone ("whines": a fan's blade rate,
// a charger's switching frequency, a motor driver's PWM).
//
// Each whine is a sine at a frequency and an RMS level in dBFS as recorded (a full-scale
// sine reads -3 dBFS RMS, as for the noise in sim/noise.h); its phase is drawn from
// the channel's seed. The sines are computed from the sample count (not by recursion), so
// a stream of any length stays exactly on frequency and level.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dtmf::sim {

struct Whine {
  double frequency_hz = 0;
  double level_dbfs = -40;  // RMS of the sine at the microphone
};

// "HZ:DBFS", e.g. "9000:-45"; std::invalid_argument saying what is wrong otherwise.
Whine parse_whine(const std::string& text);

class WhineSource {
 public:
  // Throws std::invalid_argument for a frequency not within (0, rate/2) or a level above 0 dBFS.
  WhineSource(std::vector<Whine> whines, int sample_rate_hz, std::uint64_t seed);
  void add_to(std::span<float> out);
  bool empty() const { return whines_.empty(); }

 private:
  struct Tone {
    double cycles_per_sample;
    double amplitude;
    double phase_cycles;
  };
  std::vector<Whine> whines_;
  std::vector<Tone> tones_;
  long long position_ = 0;
};

}  // namespace dtmf::sim
