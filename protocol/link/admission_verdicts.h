// The robot's verdicts on a frame, shared by the parts of FrameAdmission (frame_admission.cpp,
// room_stop_admission.cpp, renewal_admission.cpp): a refusal and its reason, and a refusal of
// a frame this robot cannot check, left for the robot it may be for. Header-only, internal.
#pragma once

#include <cstdint>
#include <string>

#include "link/reception.h"

namespace dtmf::link::admission {

inline void refuse(Reception& r, RefusalReason reason, std::string why) {
  r.event = ReceptionEvent::Refused;
  r.refusal = reason;
  r.detail = std::move(why);
}

// A frame this robot cannot check may be another robot's (its own key, or none): refused
// here, and left for that robot to answer.
inline void refuse_unchecked(Reception& r, std::string why) {
  refuse(r, RefusalReason::Authentication, std::move(why));
  r.answered = false;
}

// A velocity's lease, from a frame that began at `start_ms` (the robot counts it so).
inline double lease_end(const command::Velocity& velocity, double start_ms) {
  return start_ms + 1000 * velocity.lease_s;
}

// How far `counter` lies ahead of the robot's clock, for the log: "86400 s ahead of this
// robot's clock (the margin: 600 s)".
std::string ahead_of_clock_words(std::uint64_t counter, std::uint64_t clock_counter);

}  // namespace dtmf::link::admission
