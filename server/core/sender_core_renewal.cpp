// SenderCore: joint renewals (docs/protocol.md §10, "Renewing leases together"). Teleop
// streams keep their robots renewed; the core renews every kept robot in one frame whenever
// one of them is due (renewal_schedule.h), before the queue's next command, or between the
// frames (and retransmissions) of the command on air.
#include <spdlog/spdlog.h>

#include <algorithm>

#include "reliability/renewal_frame.h"
#include "sender_core.h"

namespace dtmf::server {

namespace {
// How long a renewal that is due waits for the commands queued before it: a renewal is due
// at most 400 ms after the last (teleop_stream.cpp), well within a lease of 1 s, and a key
// press's frame is worth more now.
constexpr double kRenewalSlackMs = 100;
// A renewal's frame (102.5 ms, keyed 153.75) and the capture latency (reliability::kOwnLatencyMs)
// before its robot has heard it: it must be heard before the lease runs out.
constexpr double kRenewalHeardMs = 250;
// A wait for an answer lasts at least its answer's sound and this after the frame: the robots'
// answers are heard 19-55 ms after their frames end (fleet_load.sh's runs; docs/protocol.md §9).
constexpr double kAnswerSoonMs = 150;
}  // namespace

bool SenderCore::keep_renewed(RobotIndex robot, const LinkProfile& profile, double every_ms, double lease_ms,
                              double now_ms) {
  const link::Link& renewing = link_for(profile, robot);
  if (!renewing.renews_jointly()) return false;
  Robot& r = robots_.at(robot);
  r.renewal_link = &renewing;
  renewals_.keep(robot, every_ms, lease_ms, r.frame_started_ms.value_or(now_ms));
  return true;
}

void SenderCore::stop_renewing(RobotIndex robot) {
  renewals_.drop(robot);
  robots_.at(robot).renewal_link = nullptr;
  // A renewal still waiting for the air renews only robots whose streams go on: one that
  // went out after its stream ended once stopped a robot 1327 ms after its client was killed
  // (dtmf-bench-teleop, bound 1200 ms). Its other robots are due again at once (they count
  // renewed only when it plays): the next renewal leaves this one out. Played already,
  // dropping changes nothing.
  if (sending_ && sending_->job->renewal() && !all_kept(sending_->job->renewed())) sending_->dropped = true;
}

std::vector<RobotIndex> SenderCore::renewals_due(double now_ms) const {
  if (queue_.empty()) return renewals_.due(now_ms, reliability::kRenewalSlots);
  if (std::holds_alternative<command::Stop>(queue_.front()->command())) return {};
  // A command waiting goes first (a key press: a new target) while the renewal can wait.
  return renewals_.due(now_ms - kRenewalSlackMs, reliability::kRenewalSlots);
}

double SenderCore::answer_wait_end_ms(const Job& job, double frame_end_ms, double deadline_ms) const {
  // Not the seed's word frames: their answers come up to 1.4 s after the chord.
  if (job.frames().empty() || job.frames().front()->word) return deadline_ms;
  const std::optional<double> lease_end_ms = renewals_.first_lease_end_ms();
  if (!lease_end_ms) return deadline_ms;
  // An answer lost holds the air until the deadline, and no renewal may interrupt a wait: a
  // lost ACK after a key press once held it 500 ms past a renewal's time, and a robot stood
  // still. The wait ends when the renewal must go to be heard within the lease; by then an
  // answer that was coming has come.
  const double soonest_ms = frame_end_ms + job.profile().timing.ack_ms + kAnswerSoonMs;
  return std::min(deadline_ms, std::max(soonest_ms, *lease_end_ms - kRenewalHeardMs));
}

bool SenderCore::all_kept(const std::vector<Job::Renewed>& renewed) const {
  return std::all_of(renewed.begin(), renewed.end(), [this](const Job::Renewed& r) { return renewals_.kept(r.index); });
}

void SenderCore::frame_started(const Job& job, double at_ms) {
  if (job.renewal()) {
    for (const Job::Renewed& r : job.renewed()) {
      renewals_.frame_started(r.index, at_ms);
      robots_[r.index].renewed_ms = at_ms;
      robots_[r.index].frame_started_ms = at_ms;
    }
    return;
  }
  const RobotIndex robot = robot_of(job.link());
  renewals_.frame_started(robot, at_ms);
  robots_[robot].frame_started_ms = at_ms;
}

bool SenderCore::start_renewal(const std::vector<RobotIndex>& robots, double now_ms) {
  std::vector<link::Link*> links;
  for (const RobotIndex r : robots) {
    // Kept under one profile each; links keyed otherwise than the first's are left out: one
    // frame renews keyed robots or plain ones, never both (link/renewal_planner.h).
    const link::Link* kept = robots_[r].renewal_link;
    if (!kept || (!links.empty() && kept->keyed() != links.front()->keyed())) continue;
    links.push_back(&link_for(kept->profile(), r));  // the robot's own link, which numbers its frames
  }
  std::optional<link::Link::PlannedRenewal> planned;
  try {
    if (!links.empty()) planned = links.front()->plan_renewal(links);
  } catch (const std::exception& e) {  // the counter's store failed: no frame can be numbered
    spdlog::error("a joint renewal cannot number its frame: {}", e.what());
  }
  std::vector<Job::Renewed> renewed;
  if (planned) {
    for (const std::size_t i : planned->renewed) {
      const RobotIndex r = robot_of(*links[i]);
      renewed.push_back({r, robots_[r].name, links[i]->options().address});
    }
  }
  // Those left out (nothing to renew, a counter they could not complete) are not due again
  // until their period has passed once more: their streams renew them with frames of their own.
  // Those renewed count from the frame's start (play()): a renewal dropped while it waits
  // for the air (stop_renewing) leaves them due.
  for (const RobotIndex r : robots)
    if (std::none_of(renewed.begin(), renewed.end(), [r](const Job::Renewed& e) { return e.index == r; }))
      renewals_.frame_started(r, now_ms);
  if (renewed.empty()) return false;
  link::Link& first = *links[planned->renewed.front()];
  auto job = std::make_shared<Job>(first, std::move(planned->frame), std::move(renewed), run_id_);
  ProgressEvent queued{ProgressEvent::Kind::Queued};
  queued.frame_count = 1;
  emit(job, queued, now_ms);
  between_ = std::exchange(sending_, Sending{job});
  // A stream that ended while the frame was planned: the next renewal leaves its robot out.
  if (!all_kept(sending_->job->renewed())) sending_->dropped = true;
  return true;
}

}  // namespace dtmf::server
