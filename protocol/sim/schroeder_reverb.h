// Physical layer: the first simulated room, a diffuse reverberator (Schroeder 1962: four
// parallel feedback combs, then two all-passes) tuned to an RT60, mixed in at a wet level.
//
// It gives a tail that decays at the right rate but no early reflections and hardly any
// frequency-selective fading (its response is the direct sound plus a weak, dense tail;
// see tests/sim/room_fading_test.cpp). Kept for the benchmarks and experiments that
// were measured with it; the rooms of room_model.h replace it where fading matters.
#pragma once

#include <span>
#include <vector>

namespace dtmf::sim {

struct ReverbConfig {
  double rt60_s = 0;  // 0: no reverberation
  double wet = 0.3;   // level of the reverberant sound against the direct sound
};

class SchroederReverb {
 public:
  SchroederReverb(const ReverbConfig& config, int sample_rate_hz);
  // In place: x becomes x + wet * reverb(x).
  void process(std::span<float> x);

 private:
  struct Line {
    std::vector<float> buffer;
    std::size_t pos = 0;
    float feedback;
  };
  std::vector<Line> combs_;
  std::vector<Line> allpasses_;
  float wet_;
};

}  // namespace dtmf::sim
