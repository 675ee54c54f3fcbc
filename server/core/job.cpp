#include "job.h"

#include <utility>

namespace dtmf::server {

std::string outcome_name(Outcome outcome) {
  switch (outcome) {
    case Outcome::Pending:
      return "pending";
    case Outcome::Confirmed:
      return "confirmed";
    case Outcome::Continued:
      return "continued";
    case Outcome::Failed:
      return "failed";
    case Outcome::Cancelled:
      return "cancelled";
    case Outcome::Unavailable:
      return "failed";
    case Outcome::Sent:
      return "sent";
  }
  return "failed";
}

Job::Job(link::Link& link, command::Command command, Policy policy, std::chrono::milliseconds decision_timeout,
         std::optional<std::string> run_id)
    : link_(link),
      command_(std::move(command)),
      command_frames_(link.frame_count(command_)),
      policy_(policy),
      decision_timeout_(decision_timeout),
      run_id_(std::move(run_id)) {}

Job::Job(link::Link& link, link::TransmitFrame renewal, std::vector<Renewed> robots, std::optional<std::string> run_id)
    : link_(link),
      command_(command::Velocity{0, 0, 1.0}),
      command_frames_(1),
      policy_(Policy::Unanswered),
      decision_timeout_(0),
      run_id_(std::move(run_id)),
      renewed_(std::move(robots)) {
  frames_.push_back(std::make_shared<const link::TransmitFrame>(std::move(renewal)));
}

void Job::plan() {
  if (renewal()) return;  // planned when made
  for (link::TransmitFrame& f : link_.plan(command_))
    frames_.push_back(std::make_shared<const link::TransmitFrame>(std::move(f)));
}

int Job::frame_count() const { return static_cast<int>(frames_.empty() ? command_frames_ : frames_.size()); }

// What the robot will execute: the command as its parameter fields carry it.
std::string Job::description() const {
  if (!renewal()) return command::describe(link_.as_received(command_));
  std::string names;
  for (const Renewed& r : renewed_) names += (names.empty() ? "" : ", ") + r.robot;
  return "renewal of " + names;
}

std::optional<ProgressEvent> Job::next_event(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [this] { return !events_.empty() || outcome_ != Outcome::Pending; });
  if (events_.empty()) return std::nullopt;
  ProgressEvent event = std::move(events_.front());
  events_.pop_front();
  return event;
}

std::optional<ProgressEvent> Job::take_event() {
  std::lock_guard lock(mutex_);
  if (events_.empty()) return std::nullopt;
  ProgressEvent event = std::move(events_.front());
  events_.pop_front();
  return event;
}

void Job::on_event(std::function<void()> told) {
  std::lock_guard lock(mutex_);
  told_ = std::move(told);
}

void Job::tell() {
  std::function<void()> told;
  {
    std::lock_guard lock(mutex_);
    told = told_;
  }
  if (told) told();
}

bool Job::finished_and_drained() {
  std::lock_guard lock(mutex_);
  return outcome_ != Outcome::Pending && events_.empty();
}

void Job::cancel() {
  {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  changed_.notify_all();
  woken();
}

bool Job::cancelled() {
  std::lock_guard lock(mutex_);
  return cancelled_;
}

void Job::overtake() {
  {
    std::lock_guard lock(mutex_);
    cancelled_ = overtaken_ = true;
  }
  changed_.notify_all();
}

bool Job::overtaken() {
  std::lock_guard lock(mutex_);
  return overtaken_;
}

bool Job::decide(reliability::Decision decision) {
  {
    std::lock_guard lock(mutex_);
    if (!awaiting_decision_) return false;
    decision_ = decision;
    awaiting_decision_ = false;
  }
  changed_.notify_all();
  woken();
  return true;
}

void Job::open_decision() {
  std::lock_guard lock(mutex_);
  awaiting_decision_ = true;
  decision_.reset();
}

std::optional<reliability::Decision> Job::take_decision() {
  std::lock_guard lock(mutex_);
  if (decision_) awaiting_decision_ = false;
  return std::exchange(decision_, std::nullopt);
}

void Job::on_change(std::function<void()> wake) {
  std::lock_guard lock(mutex_);
  wake_ = std::move(wake);
}

void Job::woken() {
  std::function<void()> wake;
  {
    std::lock_guard lock(mutex_);
    wake = wake_;
  }
  if (wake) wake();
}

Outcome Job::outcome() {
  std::lock_guard lock(mutex_);
  return outcome_;
}

std::string Job::outcome_detail() {
  std::lock_guard lock(mutex_);
  return outcome_detail_;
}

void Job::emit(ProgressEvent event) {
  {
    std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
  }
  changed_.notify_all();
  tell();
}

void Job::finish(Outcome outcome, std::string detail) {
  {
    std::lock_guard lock(mutex_);
    outcome_ = outcome;
    outcome_detail_ = std::move(detail);
  }
  changed_.notify_all();
  tell();
}

}  // namespace dtmf::server
