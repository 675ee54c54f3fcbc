// When the sender renews its robots' velocity leases jointly (docs/protocol.md §10, "Renewing
// leases together"), as pure state: which robots a Teleop stream keeps renewed and how often,
// and when each robot's last frame began (any frame for it counts: a velocity frame renews
// its lease too). When one of them is due, all of them are renewed in one frame, the longest
// unrenewed first, as many as a frame holds: a frame costs the same for one robot as for three,
// and renewing them together keeps them due together. It also keeps each robot's lease, so
// that the sender can end a wait for an answer that would outlast one (first_lease_end_ms()).
// No I/O, no clock: times are passed in.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <vector>

namespace dtmf::server {

class RenewalSchedule {
 public:
  using Robot = std::size_t;

  // Keeps `robot`, whose velocity holds for `lease_ms` from its frame's start, renewed every
  // `every_ms` from now on (or from its last frame, if it had one).
  void keep(Robot robot, double every_ms, double lease_ms, double now_ms);
  void drop(Robot robot);
  bool kept(Robot robot) const { return robots_.contains(robot); }
  // A frame for `robot` began at `at_ms` (a velocity frame, or a renewal it was in).
  void frame_started(Robot robot, double at_ms);
  // The robots to renew now, if any is due: up to `most`, the longest unrenewed first.
  std::vector<Robot> due(double now_ms, std::size_t most) const;
  // When the first kept robot's lease runs out unless renewed; nothing while no robot is kept.
  std::optional<double> first_lease_end_ms() const;
  // When the next one falls due; nothing while no robot is kept.
  std::optional<double> next_due_ms() const;

 private:
  struct Kept {
    double every_ms = 0;
    double lease_ms = 0;
    double last_ms = 0;
  };
  std::vector<Robot> oldest(std::size_t most) const;
  std::map<Robot, Kept> robots_;
};

}  // namespace dtmf::server
