// Which reply lane an answer sounds in (the fast profile; signal/hop_reply.h). The ACK to a
// frame numbered `number` (its sequence number, or with a key its counter) sounds in lane
// number mod 2: consecutive frames alternate lanes, so an answer never sounds on the bins the
// last answer's reverberant tail still fills (docs/protocol.md, "Answers in reverberant
// rooms"). A NACK names no frame and sounds in lane 0. Pure logic.
#pragma once

#include <cstdint>

#include "profile/link_profile.h"

namespace dtmf::link {

inline int answer_lane(std::uint64_t number) { return static_cast<int>(number % HopPlan::kReplyLanes); }
inline constexpr int kNackLane = 0;

}  // namespace dtmf::link
