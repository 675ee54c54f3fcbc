// Physical layer: a transmitter moving towards or away from the microphone (the robot
// driving while it listens), as a time-varying delay and level on that transmitter's path.
//
// The distance changes at a constant radial speed and turns back at `min_distance_m` and
// `max_distance_m`, so a stream of any length stays within the room (0.22 m/s, the
// TurtleBot3's top speed, covers 0.5 to 20 m in 89 s). The sound heard at time t left the
// loudspeaker d(t)/c earlier: a delay line read at a fractional position (a 32-tap
// Kaiser-windowed sinc, flat to 0.1 dB up to 20 kHz at 48 kHz) whose delay grows by v/c
// every second, which is the Doppler shift f' = f (1 - v/c) (the difference to the exact
// moving-source formula is of order (v/c)^2, 4e-7 at 0.22 m/s). The level follows 1/d(t),
// relative to the starting distance, whose level the rest of the path already applies.
// Every output sample depends only on its index, never on how the stream was split.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace dtmf::sim {

struct RadialMotion {
  double speed_mps = 0;  // > 0 moving away first, < 0 approaching first, 0 standing still
  double min_distance_m = 0.5;
  double max_distance_m = 20;
};

inline constexpr int kMovingDelayHalfTaps = 16;

class MovingDelay {
 public:
  // For a path that delays by offset_samples more after this line, so that the sound
  // heard at time t (this line's sample t * rate - offset_samples) left d(t) / c before:
  // the delay here is d(t) / c * rate - offset_samples, which must stay at or above
  // kMovingDelayHalfTaps (the interpolator looks that far ahead); choose offset_samples
  // so. Throws std::invalid_argument for a start outside [min, max] or a speed beyond 50 m/s.
  MovingDelay(const RadialMotion& motion, double start_distance_m, double offset_samples, int sample_rate_hz);

  // out[i] = in delayed as above and scaled by start / d(t).
  void process(std::span<const float> in, std::span<float> out);

  // Distance at `t_s` seconds into the stream.
  double distance_m(double t_s) const;

 private:
  RadialMotion motion_;
  double start_m_;
  double offset_samples_;
  int sample_rate_hz_;
  long long produced_ = 0;      // output samples so far
  long long base_ = 0;          // stream index of history_[0]
  std::vector<float> history_;  // input not yet passed by every read position
};

}  // namespace dtmf::sim
