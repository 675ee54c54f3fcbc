// Transmitter::stop_overtakes: a Stop ends what it stops. No renewal of a stopped robot's
// lease goes out after it. The command on air is overtaken, whichever robot it is for: its
// answer wait, retransmissions and a decision could hold the air for seconds (as long as a
// caller takes to decide), and a Stop must be on air within a frame. The commands queued for
// the stopped robot (every robot's, for a stop for every robot) are overtaken too: behind the
// stop they would set it moving again. Commands for other robots stay queued, behind the stop.
#include "transmitter.h"

namespace dtmf::server {

std::vector<std::shared_ptr<Job>> Transmitter::stop_overtakes(const link::Link& link, const command::Command& stop) {
  const bool every = command::every_robot(stop);
  const auto stops = [&](RobotIndex r) { return every || robot_of(link) == r; };
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    if (!stops(r)) continue;
    renewals_.drop(r);
    robots_[r].renewal_link = nullptr;
  }
  const auto is_stop = [](const Job& job) { return std::holds_alternative<command::Stop>(job.command()); };
  std::vector<std::shared_ptr<Job>> overtaken;
  if (on_air_ && !is_stop(*on_air_)) {
    overtaken.push_back(on_air_);
    stop_waiting_ = true;  // ends its answer wait (wait_reply)
  }
  for (const auto& queued : queue_) {
    if (!is_stop(*queued) && stops(robot_of(queued->link()))) overtaken.push_back(queued);
  }
  return overtaken;
}

}  // namespace dtmf::server
