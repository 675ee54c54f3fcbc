// What a robot's receiver makes of one frame's audio heard alone: after 100 ms of silence,
// and followed by 600 ms more (the time its answer takes), fed in the receiver's blocks.
#pragma once

#include <span>
#include <vector>

#include "link/link.h"

namespace test_support {

inline std::vector<dtmf::link::Reception> hear_alone(const dtmf::link::Link& robot, dtmf::link::FrameReceiver& receiver,
                                                     const std::vector<float>& audio) {
  const dtmf::LinkProfile& p = robot.profile();
  std::vector<float> track(static_cast<std::size_t>(p.samples_for_ms(100)), 0.0f);
  track.insert(track.end(), audio.begin(), audio.end());
  track.resize(track.size() + static_cast<std::size_t>(p.samples_for_ms(600)), 0.0f);
  std::vector<dtmf::link::Reception> got;
  const auto block = static_cast<std::size_t>(robot.receiver_block_samples());
  for (std::size_t at = 0; at + block <= track.size(); at += block) {
    for (const auto& r : receiver.feed(std::span<const float>(track).subspan(at, block))) got.push_back(r);
  }
  return got;
}

}  // namespace test_support
