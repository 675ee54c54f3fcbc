// TeleopService::ListRobots: the robots this sender drives, from its transmitter.
#include "teleop_service.h"

namespace dtmf::server {

grpc::Status TeleopService::ListRobots(grpc::ServerContext*, const v1::ListRobotsRequest*,
                                       v1::ListRobotsResponse* response) {
  for (const RobotStatus& s : transmitter_.robots()) {
    v1::Robot* robot = response->add_robots();
    robot->set_name(s.name);
    robot->set_address(s.address);
    robot->set_key_id(s.key_id);
    robot->set_model(s.model);
    if (s.last_answered) {
      robot->set_last_answered_unix_ms(
          std::chrono::duration_cast<std::chrono::milliseconds>(s.last_answered->time_since_epoch()).count());
    }
  }
  return grpc::Status::OK;
}

}  // namespace dtmf::server
