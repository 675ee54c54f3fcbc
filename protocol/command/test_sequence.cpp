#include "command/test_sequence.h"

#include "command/word_codec.h"

namespace dtmf::command {

std::vector<Command> seed_test_sequence() {
  std::vector<Command> sequence;
  for (int i = 0; i < 5; ++i) sequence.emplace_back(Reset{});
  for (auto [speed, duration] : {std::pair{20.0, 1.0}, {40.0, 1.5}, {60.0, 2.0}, {80.0, 1.0}, {100.0, 0.5}}) {
    sequence.emplace_back(DriveForDuration{speed, duration});
  }
  for (auto [rotation, duration] : {std::pair{-100.0, 1.0}, {-50.0, 1.0}, {25.0, 2.0}, {50.0, 1.0}, {100.0, 0.5}}) {
    sequence.emplace_back(TurnForDuration{rotation, duration});
  }
  for (double speed : {25.0, 50.0, 75.0}) {
    sequence.emplace_back(DriveForward{speed});
    sequence.emplace_back(Stop{});
  }
  for (double rotation : {-50.0, 50.0, 100.0}) {
    sequence.emplace_back(Turn{rotation});
    sequence.emplace_back(Stop{});
  }
  return sequence;
}

std::size_t frame_count(const std::vector<Command>& commands) {
  std::size_t frames = 0;
  for (const Command& c : commands) frames += encode(c).size();
  return frames;
}

}  // namespace dtmf::command
