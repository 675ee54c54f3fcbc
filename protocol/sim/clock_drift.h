// Physical layer: the microphone's clock running fast or slow against the loudspeakers'.
//
// A microphone whose clock runs `ppm` parts per million fast records 1 + ppm * 1e-6 samples
// for every sample of the air, so it hears every tone lower by the same fraction and the
// recording lasts longer. The air's samples are resampled by that ratio with libsamplerate
// (medium-quality sinc: flat to 90 % of Nyquist, aliases 97 dB down), streaming. Why not
// an interpolating polynomial (the first version used Catmull-Rom): at 16 kHz, a third of
// a 48 kHz rate, a cubic interpolator loses 3.3 dB midway between samples, so at 3000 ppm
// the top tones came out amplitude-modulated at 144 Hz with sidebands about 15 dB down.
//
// The sinc looks ahead a few dozen samples, so the first calls return that many samples
// fewer than they are given (the signal itself is not delayed); the output depends only on
// the input stream, never on how it was split into calls.
#pragma once

#include <span>
#include <vector>

namespace dtmf::sim {

inline constexpr double kMaxClockOffsetPpm = 10000;

class ClockDrift {
 public:
  // Throws std::invalid_argument beyond +-kMaxClockOffsetPpm.
  explicit ClockDrift(double ppm);
  ~ClockDrift();
  ClockDrift(const ClockDrift&) = delete;
  ClockDrift& operator=(const ClockDrift&) = delete;

  // Appends the microphone's samples for these samples of the air to `out`.
  void process(std::span<const float> air, std::vector<float>& out);

 private:
  double ratio_;
  void* state_;
  std::vector<float> buffer_;
};

}  // namespace dtmf::sim
