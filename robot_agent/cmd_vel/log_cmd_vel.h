// cmd_vel output `log`: one JSON object per published velocity, one per line.
//   {"t_ms":2150.0,"stamp":"2026-…Z","linear_mps":0.11,"angular_radps":0.0,"angular_rps":0.0}  (angular_rps: the old
//   name, until 0.2)
#pragma once

#include <cstdio>

#include "cmd_vel/velocity.h"

namespace dtmf::agent {

class LogCmdVel : public CmdVelOutput {
 public:
  explicit LogCmdVel(std::FILE* out) : out_(out) {}
  void publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) override;

 private:
  std::FILE* out_;
};

}  // namespace dtmf::agent
