#include "command/random_command.h"

namespace dtmf::command {

Command random_command(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(rng() % 100001) / 100000.0; };
  switch (rng() % 7) {
    case 0:
      return Reset{};
    case 1:
      return Stop{};
    case 2:
      return DriveForDuration{uniform(0, 100), uniform(0, 8)};
    case 3:
      return TurnForDuration{uniform(-100, 100), uniform(0, 8)};
    case 4:
      return DriveForward{uniform(0, 100)};
    case 5:
      return Turn{uniform(-100, 100)};
    default:
      return Velocity{uniform(-1, 1), uniform(-1, 1), uniform(0.3, 2)};
  }
}

}  // namespace dtmf::command
