// Transmitter::submit_every_robot_stop: the stop every robot in the room obeys, on the room
// links (docs/security.md, "The room key"), to the front of the queue.
#include "transmitter.h"

namespace dtmf::server {

std::shared_ptr<Job> Transmitter::submit_every_robot_stop(const LinkProfile* requested) {
  link::Link* room = nullptr;
  for (const auto& l : room_links_) {
    const bool usable = l->profile().sample_rate_hz == profile_.sample_rate_hz && l->addresses_robots();
    if (requested ? &l->profile() == requested : usable) {
      if (!usable)
        throw std::invalid_argument("profile " + requested->name +
                                    " names no robot in its frames: a stop for every robot needs one that does (fast)");
      room = l.get();
      break;
    }
  }
  if (!room) throw std::invalid_argument("this server has no profile that can send a stop for every robot");
  if (!room->keyed()) {
    for (const Robot& r : robots_) {
      if (r.links.front()->keyed())
        throw RoomKeyMissing(
            "robot " + r.name +
            " has a key, and takes a stop for every robot only under the room key: make one (dtmfctl keygen "
            "room.key), give it to every robot (dtmf-agent --room-key) and to this server (dtmf-server --room-key)");
    }
  }
  return enqueue(*room, command::Stop{true}, Policy::Unanswered, std::chrono::milliseconds(0), true);
}

}  // namespace dtmf::server
