#include "command/robot_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "command/command_payload.h"
#include "command/word_codec.h"

namespace dtmf::command {

const RobotModel& burger() {
  static const RobotModel model{"burger", 0.22, 2.84};
  return model;
}

const RobotModel& waffle() {
  static const RobotModel model{"waffle", 0.26, 1.82};
  return model;
}

const RobotModel& robot_model_by_name(std::string_view name) {
  if (name == "burger") return burger();
  if (name == "waffle" || name == "waffle_pi") return waffle();
  throw std::invalid_argument("unknown robot model '" + std::string(name) + "': choose burger or waffle");
}

namespace {

// value / limit, or ParameterError naming `field` and the model's range.
double fraction_of(const RobotModel& model, const char* field, double value, double limit, const char* unit) {
  // A hair over the limit is the limit: a client that adds 0.01 steps in floating point
  // must still reach the top speed.
  if (!std::isfinite(value) || std::abs(value) > limit * (1 + 1e-9)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s %g is out of range for a %s: allowed -%g..%g %s", field, value,
                  model.name.c_str(), limit, limit, unit);
    throw ParameterError(field, buf);
  }
  return std::clamp(value / limit, -1.0, 1.0);
}

}  // namespace

Velocity velocity_command(const RobotModel& model, double linear, double angular, double lease_s) {
  Velocity v{fraction_of(model, "linear_mps", linear, model.max_linear_mps, "m/s"),
             fraction_of(model, "angular_radps", angular, model.max_angular_radps, "rad/s"), lease_s};
  if (!std::isfinite(lease_s) || lease_s < kMinLease_s || lease_s > kMaxLease_s) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "lease_s %g is out of range: allowed %g..%g s", lease_s, kMinLease_s, kMaxLease_s);
    throw ParameterError("lease_s", buf);
  }
  return v;
}

double linear_mps(const RobotModel& model, const Velocity& velocity) {
  return velocity.linear_fraction * model.max_linear_mps;
}

double angular_radps(const RobotModel& model, const Velocity& velocity) {
  return velocity.angular_fraction * model.max_angular_radps;
}

}  // namespace dtmf::command
