// The seed's system test (its section 10): 65 frames of commands, the same in every run.
//
//   5 reset commands, 5 DRIVE_FOR_DURATION, 5 TURN_FOR_DURATION, 3 DRIVE_FORWARD and
//   3 TURN — each drive or turn preceded by RESET and its mode word, each continuous one
//   followed by RESET and STOP: 5 + 5*3 + 5*3 + 3*(3+2) + 3*(3+2) = 65 frames.
// The seed gives neither the order nor the parameters; ours are in docs/protocol.md
// ("Test sequence") and spread over each mode's range so that every field is exercised.
#pragma once

#include <vector>

#include "command/command.h"

namespace dtmf::command {

std::vector<Command> seed_test_sequence();

// The number of frames the sequence takes (65).
std::size_t frame_count(const std::vector<Command>& commands);

}  // namespace dtmf::command
