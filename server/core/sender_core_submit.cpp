// SenderCore: what callers give it. Commands wait in one bounded queue; a Stop goes to its
// front and ends what it stops (stop_overtakes). The stop for every robot goes on the room
// links (docs/security.md, "The room key").
#include "sender_core.h"

#include <algorithm>

#include "command/word_codec.h"  // command::ParameterError

namespace dtmf::server {

using Kind = ProgressEvent::Kind;

Submitted SenderCore::submit(const command::Command& command, Policy policy, std::chrono::milliseconds decision_timeout,
                             bool to_front, const LinkProfile* profile, RobotIndex robot, double now_ms) {
  const LinkProfile* sent = nullptr;
  try {
    sent = &sendable_profile(profile, std::holds_alternative<command::Stop>(command), robot);
  } catch (const UnauthenticatedRefused& e) {
    return Refusal(Refusal::Kind::Unauthenticated, e.what());
  } catch (const std::invalid_argument& e) {  // a profile it cannot send, or not to this robot
    return Refusal(Refusal::Kind::NoProfile, e.what());
  }
  try {
    return enqueue(link_for(*sent, robot), command, policy, decision_timeout, to_front, now_ms);
  } catch (const command::ParameterError& e) {
    // The profile's frames cannot carry the command (its fields, or its kind).
    return Refusal(Refusal::Kind::Unsendable, "profile " + sent->name + ": " + e.what());
  }
}

Submitted SenderCore::submit_every_robot_stop(const LinkProfile* requested, double now_ms) {
  link::Link* room = nullptr;
  for (const auto& l : room_links_) {
    const bool usable = l->profile().sample_rate_hz == profile_.sample_rate_hz && l->addresses_robots();
    if (requested ? &l->profile() == requested : usable) {
      if (!usable)
        return Refusal(Refusal::Kind::NoProfile,
                       "profile " + requested->name +
                           " names no robot in its frames: a stop for every robot needs one that does (fast)");
      room = l.get();
      break;
    }
  }
  if (!room)
    return Refusal(Refusal::Kind::NoProfile, "this server has no profile that can send a stop for every robot");
  if (!room->keyed()) {
    for (const Robot& r : robots_) {
      if (r.links.front()->keyed())
        return Refusal(
            Refusal::Kind::RoomKeyMissing,
            "robot " + r.name +
                " has a key, and takes a stop for every robot only under the room key: make one (dtmfctl keygen "
                "room.key), give it to every robot (dtmf-agent --room-key) and to this server (dtmf-server "
                "--room-key)");
    }
  }
  return enqueue(*room, command::Stop{true}, Policy::Unanswered, std::chrono::milliseconds(0), true, now_ms);
}

Submitted SenderCore::enqueue(link::Link& link, const command::Command& command, Policy policy,
                              std::chrono::milliseconds decision_timeout, bool to_front, double now_ms) {
  const bool stop = std::holds_alternative<command::Stop>(command);
  auto job = std::make_shared<Job>(link, command, policy, decision_timeout, run_id_);
  if (!command::every_robot(command)) job->set_robot(robots_[robot_of(link)].name);
  if (stopping_) return Refusal(Refusal::Kind::Unavailable, "the server is shutting down");
  if (!unavailable_.empty()) return Refusal(Refusal::Kind::Unavailable, unavailable_);
  // A stop is never refused for a full queue: it goes first, and what it stops waits behind it.
  if (queue_.size() >= options_.max_queue && !stop) {
    return Refusal(Refusal::Kind::QueueFull, "the transmit queue is full (" + std::to_string(options_.max_queue) +
                                                 " commands wait); retry later, or send Stop, which goes first");
  }
  if (stop) {
    for (const auto& o : stop_overtakes(link, command)) o->overtake();
  }
  // Queued comes before anything the loudspeaker does with it.
  ProgressEvent queued{Kind::Queued};
  queued.frame_count = job->frame_count();
  queued.queue_position = (to_front ? 0 : static_cast<int>(queue_.size())) + (sending_ ? 1 : 0);
  emit(job, queued, now_ms);
  if (to_front)
    queue_.push_front(job);
  else
    queue_.push_back(job);
  return job;
}

void SenderCore::withdraw(const Job& job, double now_ms) {
  std::erase_if(queue_, [&job](const auto& queued) { return queued.get() == &job; });
  std::erase_if(events_, [&job](const Emitted& e) { return e.job.get() == &job; });
  if (!sending_ || sending_->job.get() != &job) return;
  // A renewal taken back before it played: its robots are not due again at once, to fail again.
  for (const Job::Renewed& r : job.renewed()) renewals_.frame_started(r.index, now_ms);
  sending_ = std::exchange(between_, std::nullopt);
}

// A Stop ends what it stops. No renewal of a stopped robot's lease goes out after it. The
// command on air is overtaken, whichever robot it is for: its answer wait, retransmissions and
// a decision could hold the air for seconds (as long as a caller takes to decide), and a Stop
// must be on air within a frame. The commands queued for the stopped robot (every robot's,
// for a stop for every robot) are overtaken too: behind the stop they would set it moving
// again. Commands for other robots stay queued, behind the stop.
std::vector<std::shared_ptr<Job>> SenderCore::stop_overtakes(const link::Link& link, const command::Command& stop) {
  const bool every = command::every_robot(stop);
  const auto stops = [&](RobotIndex r) { return every || robot_of(link) == r; };
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    if (!stops(r)) continue;
    renewals_.drop(r);
    robots_[r].renewal_link = nullptr;
  }
  const auto is_stop = [](const Job& job) { return std::holds_alternative<command::Stop>(job.command()); };
  std::vector<std::shared_ptr<Job>> overtaken;
  for (const std::optional<Sending>* on : {&sending_, &between_}) {
    if (*on && !is_stop(*(*on)->job)) {
      overtaken.push_back((*on)->job);
      stop_waiting_ = true;  // ends its answer wait
    }
  }
  for (const auto& queued : queue_) {
    if (!is_stop(*queued) && stops(robot_of(queued->link()))) overtaken.push_back(queued);
  }
  return overtaken;
}

void SenderCore::emit(const std::shared_ptr<Job>& job, ProgressEvent event, double at_ms) {
  event.at_ms = at_ms;
  events_.push_back({job, std::move(event)});
}

}  // namespace dtmf::server
