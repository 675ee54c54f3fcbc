// Application layer (robot): a velocity for the wheels, as cmd_vel carries it.
#pragma once

#include <chrono>

namespace dtmf::agent {

struct Velocity {
  double linear_mps = 0;     // forward, m/s (geometry_msgs Twist linear.x)
  double angular_radps = 0;  // counter-clockwise, rad/s (Twist angular.z)
  bool operator==(const Velocity&) const = default;
};

// Where velocities go: the real robot (DDS), a simulated one, a log. `audio_ms` is the
// agent's clock (milliseconds of audio heard since start); `stamp` the matching wall time.
class CmdVelOutput {
 public:
  virtual ~CmdVelOutput() = default;
  virtual void publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) = 0;
};

}  // namespace dtmf::agent
