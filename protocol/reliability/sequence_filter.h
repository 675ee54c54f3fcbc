// Reliability layer: the robot's memory of the last frame it executed.
//
// The sender gives every new command the next sequence number (mod 16) and repeats the
// number only when it retransmits the same frame after a lost ACK. So a frame whose
// sequence number and bits equal the last executed frame's is that frame again: the robot
// answers it (the ACK may have been what was lost) but does not execute it a second time.
// Only the last frame is remembered, which is all stop-and-wait needs.
// Pure logic: no I/O, no clock.
#pragma once

#include <cstdint>
#include <optional>

#include "reliability/command_frame.h"

namespace dtmf::reliability {

class SequenceFilter {
 public:
  // True when `frame` is the last one executed, again. Changes nothing.
  bool is_repeat(const CommandFrame& frame) const { return last_ && *last_ == frame; }
  // True when `frame` is new and should be executed; remembers it.
  bool first_time(const CommandFrame& frame) {
    if (is_repeat(frame)) return false;
    last_ = frame;
    return true;
  }
  void reset() { last_.reset(); }

 private:
  std::optional<CommandFrame> last_;
};

}  // namespace dtmf::reliability
