// dtmf-room's real-time keeper: how much of what was just read to drop, so that the filter
// never holds sound back.
//
// The filter's input is a PulseAudio recording (parec), which keeps whatever was not read in
// time, and its output a playback stream (pacat), which plays silence while it waits. After
// any stall of the chain (the filter, a bridge, the machine), the stalled audio stays queued
// upstream while the playback side blocks each write at real-time pace, so every later sound
// arrives late by the stall, for good: in scripts/experiments runs the delay through one
// bridge grew from 370 to 870 ms within 70 s, and the fast profile's 500 ms ACK timeout then
// expired on every frame. A real room holds nothing back. So: the lag of the input behind the
// wall clock is tracked against the least lag seen, and past `allowance_ms` the queued audio
// is dropped, as a loudspeaker that fell silent for the stall would have lost it.
// Pure logic: the caller passes the clock.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace dtmf::room {

class LagKeeper {
 public:
  LagKeeper(int sample_rate_hz, double allowance_ms) : rate_hz_(sample_rate_hz), allowance_ms_(allowance_ms) {}

  // `samples` were just read at `now_ms` (a monotonic clock, milliseconds): how many of them,
  // from the front, to drop.
  std::size_t to_drop(double now_ms, std::size_t samples) {
    if (std::isnan(first_ms_)) first_ms_ = now_ms;
    const double block_ms = 1000.0 * static_cast<double>(samples) / rate_hz_;
    audio_ms_ += block_ms;
    const double lag_ms = (now_ms - first_ms_) - audio_ms_;
    least_lag_ms_ = std::min(least_lag_ms_, lag_ms);
    const double excess_ms = lag_ms - least_lag_ms_;
    // Past the allowance, catch up all the way (to a tenth of it), not just back under it:
    // else the lag would stay at the allowance and the next jitter start dropping again.
    if (excess_ms > allowance_ms_) catching_up_ = true;
    if (catching_up_ && excess_ms <= allowance_ms_ / 10) catching_up_ = false;
    if (!catching_up_) return 0;
    const auto drop = std::min(samples, static_cast<std::size_t>(excess_ms * rate_hz_ / 1000.0));
    // Dropped audio was read: the input is that much closer to the wall clock.
    dropped_ += drop;
    return drop;
  }
  // Samples dropped so far (here, and by the caller: count_dropped).
  std::size_t dropped() const { return dropped_; }
  // Input the caller read and dropped itself (it found it queued too long): read, so it
  // counts towards the input's pace.
  void skip_input(std::size_t samples) {
    audio_ms_ += 1000.0 * static_cast<double>(samples) / rate_hz_;
    dropped_ += samples;
  }
  // Output the caller dropped (its pipe was full), for the count only.
  void count_dropped_output(std::size_t samples) { dropped_ += samples; }

 private:
  int rate_hz_;
  double allowance_ms_;
  double first_ms_ = std::numeric_limits<double>::quiet_NaN();
  double audio_ms_ = 0;
  double least_lag_ms_ = std::numeric_limits<double>::infinity();
  std::size_t dropped_ = 0;
  bool catching_up_ = false;
};

}  // namespace dtmf::room
