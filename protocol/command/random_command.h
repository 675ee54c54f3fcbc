// Command abstraction layer: a random valid command (seeded), for benchmarks and tests that
// need commands of every kind (Velocity included: a teleop session's frames) with parameters
// drawn over their whole ranges.
#pragma once

#include <random>

#include "command/command.h"

namespace dtmf::command {

Command random_command(std::mt19937_64& rng);

}  // namespace dtmf::command
