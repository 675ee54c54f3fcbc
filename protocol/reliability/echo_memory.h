// Reliability layer: the robot's memory of the frames it took lately, to know their echoes.
//
// A room keeps a frame sounding after it ends: its reflections, and a reverberant tail that
// holds the tones of all its chords at once. In the quiet after it, the robot can read the
// frame again out of that tail. It did on the test air through the seminar room's measured
// response (bench/rirs): now and then the last two frames of a run were read again 0.7-0.9 s
// after they were taken, and the older of them, a new sequence number to the sequence filter,
// was executed again — a turn after the stop that followed it.
//
// A sender never sends an earlier frame after a later one: it repeats only its newest (a
// retransmission after a lost ACK) and gives every new frame the next sequence number or
// counter. So an intact frame whose bits equal those of a frame taken within the horizon,
// other than the newest, is an echo: neither executed nor answered (an answer would only
// cost air). The newest frame's echo cannot be told from its retransmission: it is answered
// and not executed again, as one (sequence_filter.h, security/freshness.h).
//
// The horizon: within it no sequence number comes round again, since the 15 new frames in
// between take at least 15 frames' air time (see docs/protocol.md, "echoes").
// Pure logic: the caller gives the times (the audio's own milliseconds).
#pragma once

#include <array>
#include <cstddef>

#include "reliability/frame_bits.h"

namespace dtmf::reliability {

class EchoMemory {
 public:
  // The frames a sequence number (mod 16) can tell apart, less the one it is.
  static constexpr std::size_t kFramesRemembered = 15;

  // `horizon_ms`: how long after it was taken a frame's bits mark an echo.
  explicit EchoMemory(double horizon_ms) : horizon_ms_(horizon_ms) {}

  // True when `bits`, heard at `heard_ms`, are those of a frame taken within the horizon
  // before, other than the newest one taken.
  bool is_echo(const FrameBits& bits, double heard_ms) const {
    for (std::size_t age = 1; age < count_; ++age) {  // age 0: the newest, which is answered
      const Taken& t = taken_[(newest_ + kFramesRemembered - age) % kFramesRemembered];
      if (heard_ms - t.heard_ms > horizon_ms_) break;  // older ones were taken earlier still
      if (t.bits == bits) return true;
    }
    return false;
  }

  // A frame was taken (executed, or a counter synchronised) at `heard_ms`.
  void remember(const FrameBits& bits, double heard_ms) {
    newest_ = count_ == 0 ? 0 : (newest_ + 1) % kFramesRemembered;
    taken_[newest_] = {bits, heard_ms};
    if (count_ < kFramesRemembered) ++count_;
  }

  double horizon_ms() const { return horizon_ms_; }

 private:
  struct Taken {
    FrameBits bits;
    double heard_ms = 0;
  };
  double horizon_ms_;
  std::array<Taken, kFramesRemembered> taken_{};
  std::size_t newest_ = 0;
  std::size_t count_ = 0;
};

}  // namespace dtmf::reliability
