#include "robot_model.h"

#include <stdexcept>

namespace dtmf::agent {

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

}  // namespace dtmf::agent
