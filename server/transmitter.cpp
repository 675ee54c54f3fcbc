// Transmitter: what callers ask of it, each passed to the core under the lock, and the core's
// events handed over in order.
#include "transmitter.h"

#include <spdlog/spdlog.h>

namespace dtmf::server {

namespace {

std::vector<RobotLinks> one_robot(std::vector<std::unique_ptr<link::Link>> links) {
  std::vector<RobotLinks> robots(1);
  robots.front().links = std::move(links);
  return robots;
}

// The core's backoff is random per sender: two senders must not draw alike.
TransmitterOptions seeded(TransmitterOptions options) {
  if (!options.backoff_seed)
    options.backoff_seed = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  return options;
}

}  // namespace

Transmitter::Transmitter(std::vector<std::unique_ptr<link::Link>> links, const LinkProfile& profile,
                         std::unique_ptr<physical::AudioSink> speaker,
                         std::unique_ptr<physical::AudioSource> microphone, ProgressObserver& observer,
                         TransmitterOptions options)
    : Transmitter(one_robot(std::move(links)), profile, std::move(speaker), std::move(microphone), observer,
                  std::move(options)) {}

Transmitter::Transmitter(std::vector<RobotLinks> robots, const LinkProfile& profile,
                         std::unique_ptr<physical::AudioSink> speaker,
                         std::unique_ptr<physical::AudioSource> microphone, ProgressObserver& observer,
                         TransmitterOptions options, std::vector<std::unique_ptr<link::Link>> room_links)
    : speaker_(std::move(speaker)),
      microphone_(std::move(microphone)),
      observer_(observer),
      realtime_audio_(options.realtime_audio),
      core_(std::move(robots), profile, seeded(std::move(options)), std::move(room_links)) {
  // The ears are built (their FFTs planned: a fast ear without FFTW wisdom measures for
  // 0.1-0.3 s of CPU, seconds on a loaded machine) before anything can be sent: built in the
  // listening thread, they came up after the first frames had gone out, and those frames'
  // answers, heard while the ear caught up, came after their deadlines. Every robot's links
  // listen: each takes only its own robot's answers (link::Link::answers).
  const std::vector<const link::Link*> every_link = core_.every_link();
  ears_ = std::make_unique<ReplyListeners>(every_link);
  worker_ = std::thread([this] { run(); });
  listener_ = std::thread([this] { listen(); });
}

Transmitter::~Transmitter() { shutdown(); }

double Transmitter::now_ms() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - epoch_).count();
}

std::chrono::steady_clock::time_point Transmitter::steady(double steady_ms) const {
  return epoch_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double, std::milli>(steady_ms));
}

store::WallTime Transmitter::wall(double steady_ms) const {
  return store::WallClock::now() +
         std::chrono::duration_cast<store::WallClock::duration>(steady(steady_ms) - std::chrono::steady_clock::now());
}

std::function<void()> Transmitter::waker() {
  return [handle = std::weak_ptr<Waking>(waking_)] {
    if (const auto alive = handle.lock()) {
      std::lock_guard lock(alive->mutex);
      if (alive->transmitter) alive->transmitter->wake();
    }
  };
}

void Transmitter::wake() {
  {
    std::lock_guard lock(mutex_);
    ++inputs_;
  }
  woken_.notify_all();
}

Submitted Transmitter::submit(const command::Command& command, Policy policy,
                              std::chrono::milliseconds decision_timeout, bool to_front, const LinkProfile* profile,
                              RobotIndex robot) {
  std::unique_lock lock(mutex_);
  return accepted(lock, core_.submit(command, policy, decision_timeout, to_front, profile, robot, now_ms()));
}

Submitted Transmitter::accepted(std::unique_lock<std::mutex>& lock, Submitted submitted) {
  auto* job = std::get_if<std::shared_ptr<Job>>(&submitted);
  if (!job) return submitted;
  (*job)->on_change(waker());
  ++inputs_;
  // Its Queued first: recorded before this call returns, or the job is taken back.
  std::optional<std::string> unrecorded = deliver(lock);
  lock.unlock();
  woken_.notify_all();
  if (unrecorded) return Refusal(Refusal::Kind::Unrecorded, *unrecorded);
  return submitted;
}

Submitted Transmitter::submit_every_robot_stop(const LinkProfile* profile) {
  std::unique_lock lock(mutex_);
  return accepted(lock, core_.submit_every_robot_stop(profile, now_ms()));
}

bool Transmitter::keep_renewed(RobotIndex robot, const LinkProfile& profile, double every_ms, double lease_ms) {
  bool kept;
  {
    std::lock_guard lock(mutex_);
    kept = core_.keep_renewed(robot, profile, every_ms, lease_ms, now_ms());
    ++inputs_;
  }
  woken_.notify_all();
  return kept;
}

void Transmitter::stop_renewing(RobotIndex robot) {
  {
    std::lock_guard lock(mutex_);
    core_.stop_renewing(robot);
    ++inputs_;
  }
  woken_.notify_all();
}

std::optional<std::chrono::steady_clock::time_point> Transmitter::last_renewed(RobotIndex robot) const {
  std::lock_guard lock(mutex_);
  const auto at_ms = core_.last_renewed_ms(robot);
  if (!at_ms) return std::nullopt;
  return steady(*at_ms);
}

bool Transmitter::decide(const std::string& command_id, reliability::Decision decision) {
  std::shared_ptr<Job> job;
  {
    std::lock_guard lock(mutex_);
    job = core_.on_air();
  }
  // Outside the lock: the job's decide() wakes the loudspeaker's thread, which takes it.
  return job && job->id() == command_id && job->decide(decision);
}

void Transmitter::set_run(std::optional<std::string> run_id) {
  std::lock_guard lock(mutex_);
  core_.set_run(std::move(run_id));
}

std::vector<RobotStatus> Transmitter::robots() const {
  std::vector<RobotStatus> all;
  std::lock_guard lock(mutex_);
  for (RobotIndex r = 0; r < core_.robot_count(); ++r) {
    const link::LinkOptions& o = core_.robot_options(r);
    RobotStatus s{core_.robot_name(r), o.address, o.key ? o.key->id_hex() : "", core_.model_of(r).name, std::nullopt};
    if (const auto at = core_.last_answered_ms(r)) s.last_answered = wall(*at);
    all.push_back(std::move(s));
  }
  return all;
}

AirShare Transmitter::air_share() const {
  std::lock_guard lock(mutex_);
  return core_.air_share();
}

std::optional<std::string> Transmitter::deliver(std::unique_lock<std::mutex>& lock) {
  std::vector<SenderCore::Emitted> events = core_.take_events();
  if (events.empty()) return std::nullopt;
  std::optional<std::string> unrecorded;
  std::unique_lock hand_over(handing_);
  // Up to the last Queued, under the core's lock: a job whose Queued cannot be recorded is
  // taken back before it can play. The rest outside it: a slow record never stalls the ears.
  std::size_t queued_end = 0;
  for (std::size_t k = 0; k < events.size(); ++k)
    if (events[k].event.kind == ProgressEvent::Kind::Queued) queued_end = k + 1;
  std::size_t i = 0;
  for (; i < queued_end; ++i) {
    if (events[i].event.kind != ProgressEvent::Kind::Queued) {
      deliver_one(events[i]);
      continue;
    }
    try {
      deliver_one(events[i]);
    } catch (const std::exception& e) {
      spdlog::error("{}: not sent, it cannot be recorded: {}", events[i].job->description(), e.what());
      core_.withdraw(*events[i].job, now_ms());
      // The caller is told (submit): a command is refused, never sent unrecorded.
      if (!events[i].job->renewal())
        unrecorded = std::string("not sent: the command cannot be recorded (") + e.what() +
                     "); check the server's database spill directory, then retry";
    }
  }
  lock.unlock();
  for (; i < events.size(); ++i) deliver_one(events[i]);
  hand_over.unlock();
  lock.lock();
  return unrecorded;
}

void Transmitter::deliver_one(SenderCore::Emitted& emitted) {
  Job& job = *emitted.job;
  ProgressEvent& event = emitted.event;
  event.time = wall(event.at_ms);
  if (event.chord_ended_ms) event.chord_ended_at = wall(*event.chord_ended_ms);
  if (event.answered_ms) event.answered_at = wall(*event.answered_ms);
  observer_.observe(job, event);
  publish_air(job, event);
  const Outcome outcome = event.outcome;
  const std::string detail = outcome != Outcome::Pending ? event.detail : std::string();
  job.emit(std::move(event));
  if (outcome != Outcome::Pending) job.finish(outcome, detail);
}

}  // namespace dtmf::server
