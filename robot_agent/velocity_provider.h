// Application layer (robot): the seed's velocity provider (its section 5, Fig. 3).
//
// Commands set a velocity and a state: IDLE (standing), DURATION (moving until an end
// time), CONTINUOUS (moving until the next command), LEASED (a teleop Velocity, held until
// its lease ends unless a newer one renews it). update() is called every publish cycle and
// returns what to publish; it ends a DURATION at its end time, a LEASED motion when its
// lease ends and — because nothing on a TurtleBot3 stops the wheels when cmd_vel goes
// quiet — a CONTINUOUS motion that has run longer than the safety limit. Inputs: speed
// 0..100 % of the model's top speed, rotation -100..100 % of its top turn rate (positive
// turns left); a Velocity's fractions of both.
//
// A Velocity, and the stop when its lease ends, are approached at the model's acceleration
// limits, so a reversal or a lost frame never jerks the wheels; the stop is timed to reach
// zero at the lease's end, never after it. The seed's commands and
// Stop take effect at once, as in the seed (Stop must never be slowed down).
// Pure logic: the caller passes the time (seconds on any steady scale).
#pragma once

#include <optional>
#include <string>

#include "cmd_vel/velocity.h"
#include "command/command.h"
#include "command/robot_model.h"

namespace dtmf::agent {

enum class MotionState { Idle, Duration, Continuous, Leased };
std::string motion_state_name(MotionState state);

class VelocityProvider {
 public:
  // continuous_limit_s: a CONTINUOUS motion stops after this long; 0 disables the limit.
  VelocityProvider(command::RobotModel model, double continuous_limit_s);

  // A complete command from the command layer, heard at now_s, its frame having started at
  // spoken_s (default: now_s). RESET changes nothing here. A Velocity's lease runs from
  // spoken_s: the frame's own airtime never lengthens it, so a sender that falls silent
  // has the robot standing still a lease after its last frame's start.
  void apply(const command::Command& command, double now_s, std::optional<double> spoken_s = std::nullopt);
  // Once per publish cycle: the velocity to publish now.
  Velocity update(double now_s);
  // Stop at once (shutdown).
  void stop();

  MotionState state() const { return state_; }
  // The wheels will still change with no new command: a timed or leased motion runs, or
  // the velocity still ramps towards its target.
  bool changing_by_itself() const;
  Velocity velocity() const { return velocity_; }
  // When the wheels next stop changing by themselves: a ramp reaching its target, or the
  // standstill at a lease's end; nothing while they hold a velocity with no end set here.
  std::optional<double> settles_at_s() const;
  // What the wheels are heading for (a Velocity's own, while they ramp towards it).
  Velocity target() const { return target_; }
  // Why the last automatic stop happened ("duration ended", "continuous limit of 30 s"), once.
  std::optional<std::string> take_stop_reason();

 private:
  Velocity drive(double speed_percent) const;
  Velocity turn(double rotation_percent) const;
  void lease(const command::Velocity& command, double now_s, double spoken_s);
  void ramp(double now_s);
  // How long the acceleration limits take to bring `from` to a standstill.
  double stopping_time_s(const Velocity& from) const;

  command::RobotModel model_;
  double continuous_limit_s_;
  MotionState state_ = MotionState::Idle;
  Velocity velocity_;  // what is published
  Velocity target_;    // what the ramp approaches (equal to velocity_ unless LEASED or after it)
  double end_s_ = 0;   // DURATION: when to stop; CONTINUOUS: when the safety limit strikes; LEASED: the lease's end
  double ramped_at_s_ = 0;
  std::optional<std::string> stop_reason_;
};

}  // namespace dtmf::agent
