#include "teleop_keys.h"

#include <algorithm>
#include <cmath>

namespace dtmf::cli {

namespace {

// Steps add up in floating point; rounding to the step keeps 0.01 * 22 at 0.22 exactly, so
// that the top speed is reachable and zero is zero.
double step(double value, double delta, double limit, double unit) {
  const double next = std::round((value + delta) / unit) * unit;
  return std::clamp(next, -limit, limit);
}

}  // namespace

KeyEffect apply_key(int key, TeleopTarget& target, const command::RobotModel& model) {
  const TeleopTarget before = target;
  switch (key) {
    case 'w':
    case 'W':
      target.linear_mps = step(target.linear_mps, kLinearStep_mps, model.max_linear_mps, kLinearStep_mps / 100);
      break;
    case 'x':
    case 'X':
      target.linear_mps = step(target.linear_mps, -kLinearStep_mps, model.max_linear_mps, kLinearStep_mps / 100);
      break;
    case 'a':
    case 'A':
      target.angular_radps =
          step(target.angular_radps, kAngularStep_radps, model.max_angular_radps, kAngularStep_radps / 100);
      break;
    case 'd':
    case 'D':
      target.angular_radps =
          step(target.angular_radps, -kAngularStep_radps, model.max_angular_radps, kAngularStep_radps / 100);
      break;
    case 's':
    case 'S':
    case ' ':
      target = {};
      break;
    case 'e':
    case 'E':
      target = {};
      return KeyEffect::StopEveryRobot;
    case 'q':
    case 'Q':
    case 3:  // Ctrl-C where the terminal passes it through
      return KeyEffect::Quit;
    default:
      return KeyEffect::None;
  }
  return target == before ? KeyEffect::None : KeyEffect::Changed;
}

}  // namespace dtmf::cli
