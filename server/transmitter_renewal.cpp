// Transmitter: joint renewals (docs/protocol.md §10, "Renewing leases together"). Teleop
// streams keep their robots renewed; the loudspeaker's thread renews every kept robot in one
// frame whenever one of them is due (renewal_schedule.h), before the queue's next command,
// or between the frames (and retransmissions) of the command on air.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "reliability/renewal_frame.h"
#include "transmitter.h"

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

bool Transmitter::keep_renewed(RobotIndex robot, const LinkProfile& profile, double every_ms, double lease_ms) {
  const link::Link& renewing = link_for(profile, robot);
  if (!renewing.renews_jointly()) return false;
  {
    std::lock_guard lock(mutex_);
    Robot& r = robots_.at(robot);
    r.renewal_link = &renewing;
    renewals_.keep(robot, every_ms, lease_ms, r.frame_started_ms.value_or(now_ms()));
  }
  changed_.notify_all();
  return true;
}

void Transmitter::stop_renewing(RobotIndex robot) {
  {
    std::lock_guard lock(mutex_);
    renewals_.drop(robot);
    robots_.at(robot).renewal_link = nullptr;
    // A renewal still waiting for the air renews only robots whose streams go on: one that
    // went out after its stream ended once stopped a robot 1327 ms after its client was killed
    // (dtmf-bench-teleop, bound 1200 ms). Its other robots are due again at once (send_renewal
    // counts them renewed only when it plays): the next renewal leaves this one out. Played
    // already, cancelling changes nothing.
    if (on_air_ && on_air_->renewal() && !all_kept(on_air_->renewed())) on_air_->cancel();
  }
  changed_.notify_all();
}

std::optional<std::chrono::steady_clock::time_point> Transmitter::last_renewed(RobotIndex robot) const {
  std::lock_guard lock(mutex_);
  const auto& at_ms = robots_.at(robot).renewed_ms;
  if (!at_ms) return std::nullopt;
  return epoch_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double, std::milli>(*at_ms));
}

std::vector<RobotIndex> Transmitter::renewals_due() const {
  if (queue_.empty()) return renewals_.due(now_ms(), reliability::kRenewalSlots);
  if (std::holds_alternative<command::Stop>(queue_.front()->command())) return {};
  // A command waiting goes first (a key press: a new target) while the renewal can wait.
  return renewals_.due(now_ms() - kRenewalSlackMs, reliability::kRenewalSlots);
}

double Transmitter::answer_wait_end_ms(const Job& job, double frame_end_ms, double deadline_ms) const {
  // Not the seed's word frames: their answers come up to 1.4 s after the chord.
  if (job.frames().empty() || job.frames().front()->word) return deadline_ms;
  std::lock_guard lock(mutex_);
  const std::optional<double> lease_end_ms = renewals_.first_lease_end_ms();
  if (!lease_end_ms) return deadline_ms;
  // An answer lost holds the air until the deadline, and no renewal may interrupt a wait: a
  // lost ACK after a key press once held it 500 ms past a renewal's time, and a robot stood
  // still. The wait ends when the renewal must go to be heard within the lease; by then an
  // answer that was coming has come.
  const double soonest_ms = frame_end_ms + job.profile().timing.ack_ms + kAnswerSoonMs;
  return std::min(deadline_ms, std::max(soonest_ms, *lease_end_ms - kRenewalHeardMs));
}

bool Transmitter::all_kept(const std::vector<Job::Renewed>& renewed) const {
  return std::all_of(renewed.begin(), renewed.end(), [this](const Job::Renewed& r) { return renewals_.kept(r.index); });
}

void Transmitter::renew_between_frames(const Job& job) {
  // Not between the seed's word frames: its robots hear a command in several frames.
  if (job.renewal() || job.frames().empty() || job.frames().front()->word) return;
  std::vector<RobotIndex> due;
  {
    std::lock_guard lock(mutex_);
    due = renewals_.due(now_ms(), reliability::kRenewalSlots);
  }
  if (!due.empty()) send_renewal(due);
}

void Transmitter::send_renewal(const std::vector<RobotIndex>& robots) {
  std::vector<link::Link*> links;
  {
    std::lock_guard lock(mutex_);
    for (const RobotIndex r : robots) {
      // Kept under one profile each; links of another profile than the first's are left out
      // (plan_renewal), and so are links keyed otherwise: one frame renews keyed robots or
      // plain ones, never both (link/renewal_planner.h).
      const link::Link* kept = robots_[r].renewal_link;
      if (!kept || (!links.empty() && kept->keyed() != links.front()->keyed())) continue;
      links.push_back(&link_for(kept->profile(), r));  // the robot's own link, which numbers its frames
    }
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
  const auto mark_started = [this](const std::vector<RobotIndex>& marked, const std::vector<Job::Renewed>& except) {
    std::lock_guard lock(mutex_);
    const double now = now_ms();
    for (const RobotIndex r : marked)
      if (std::none_of(except.begin(), except.end(), [r](const Job::Renewed& e) { return e.index == r; }))
        renewals_.frame_started(r, now);
  };
  // Those left out (nothing to renew, a counter they could not complete) are not due again
  // until their period has passed once more: their streams renew them with frames of their own.
  // Those renewed count from the frame's start (transmit()): a renewal cancelled while it waits
  // for the air (stop_renewing) leaves them due.
  mark_started(robots, renewed);
  if (renewed.empty()) return;
  link::Link& first = *links[planned->renewed.front()];
  std::shared_ptr<Job> job;
  std::shared_ptr<Job> between;  // the command whose frames it goes between, if any
  {
    std::unique_lock lock(mutex_);
    job = std::make_shared<Job>(first, std::move(planned->frame), std::move(renewed), run_id_);
    ProgressEvent queued{ProgressEvent::Kind::Queued};
    queued.frame_count = 1;
    try {
      emit(*job, queued);
    } catch (const std::exception& e) {
      // Its row cannot be recorded: nothing goes on air that the log would not show. The
      // streams renew their leases with frames of their own, which fail as visibly.
      spdlog::error("{}: not sent, it cannot be recorded: {}", job->description(), e.what());
      lock.unlock();
      mark_started(robots, {});  // not due again at once, to fail again
      return;
    }
    // A stream that ended while the frame was planned: the next renewal leaves its robot out.
    if (!all_kept(job->renewed())) job->cancel();
    between = std::exchange(on_air_, job);
  }
  send_unanswered(*job);
  std::lock_guard lock(mutex_);
  on_air_ = between;
}

}  // namespace dtmf::server
