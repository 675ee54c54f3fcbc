// Words and sums the parts of FrameAdmission share (frame_admission.cpp,
// room_stop_admission.cpp, renewal_admission.cpp): a velocity's lease end, and how far a
// counter lies past the clock, for the log. What becomes of a frame is the rules' to say
// (admission_rules.h), not these. Header-only, internal.
#pragma once

#include <cstdint>
#include <string>

#include "command/command.h"

namespace dtmf::link::admission {

// A velocity's lease, from a frame that began at `start_ms` (the robot counts it so).
inline double lease_end(const command::Velocity& velocity, double start_ms) {
  return start_ms + 1000 * velocity.lease_s;
}

// How far `counter` lies ahead of the robot's clock, for the log: "86400 s ahead of this
// robot's clock (the margin: 600 s)".
std::string ahead_of_clock_words(std::uint64_t counter, std::uint64_t clock_counter);

}  // namespace dtmf::link::admission
