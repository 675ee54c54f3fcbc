#include "transmitter.h"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace dtmf::server {

namespace {

using Kind = ProgressEvent::Kind;

std::vector<RobotLinks> one_robot(std::vector<std::unique_ptr<link::Link>> links) {
  std::vector<RobotLinks> robots(1);
  robots.front().links = std::move(links);
  return robots;
}

std::string unaddressed(const std::string& profile) {
  return "profile " + profile +
         " names no robot in its frames, and this server drives several: every robot that heard one would execute it";
}

std::string names_of(const std::vector<std::string>& names) {
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  return all;
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
    : profile_(profile),
      room_links_(room_links.empty() ? link::make_links({}) : std::move(room_links)),
      speaker_(std::move(speaker)),
      microphone_(std::move(microphone)),
      observer_(observer),
      options_(std::move(options)) {
  if (robots.empty()) throw std::invalid_argument("a sender needs a robot to drive");
  std::vector<const link::Link*> every_link;
  for (RobotLinks& given : robots) {
    Robot robot{std::move(given.name),
                std::move(given.model),
                std::move(given.links),
                {},
                std::nullopt,
                std::nullopt,
                nullptr,
                std::nullopt,
                std::nullopt};
    for (const auto& l : robot.owned_links) {
      if (l->profile().sample_rate_hz == profile_.sample_rate_hz) robot.links.push_back(l.get());
    }
    if (robot.links.empty()) throw std::invalid_argument("robot " + robot.name + " has no link at the server's rate");
    // Two robots at one address would both take its frames; two under one key would share
    // its counters, so that neither robot could complete the other's.
    const link::LinkOptions& o = robot.links.front()->options();
    for (const Robot& other : robots_) {
      const link::LinkOptions& p = other.links.front()->options();
      if (other.name == robot.name) throw std::invalid_argument("two robots are called " + robot.name);
      if (p.address == o.address)
        throw std::invalid_argument("robots " + other.name + " and " + robot.name + " share address " +
                                    std::to_string(o.address) + ": give each its own (dtmf-agent --address)");
      if (o.key && p.key && o.key->id_hex() == p.key->id_hex())
        throw std::invalid_argument("robots " + other.name + " and " + robot.name + " share key " + o.key->id_hex() +
                                    ": give each its own (dtmfctl keygen FILE)");
    }
    every_link.insert(every_link.end(), robot.links.begin(), robot.links.end());
    robots_.push_back(std::move(robot));
  }
  // The default profile must be among each robot's links, and with a key carry a MAC; with
  // several robots, name the robot.
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    const link::Link& default_link = link_for(profile_, r);
    if (robots_.size() > 1 && !default_link.addresses_robots())
      throw std::invalid_argument(unaddressed(profile_.name) + ". Choose a profile that names it (--profile fast)");
    if (default_link.keyed() && !default_link.can_authenticate() && !options_.allow_unauthenticated) {
      throw std::invalid_argument("the default profile " + profile_.name +
                                  " carries no MAC, and this sender has a key: its frames would be refused by the "
                                  "robot, and their ACKs could be played by anyone. Choose a profile that carries one "
                                  "(" +
                                  authenticated_link(r).name() + "), or allow it: --allow-unauthenticated-commands");
    }
  }
  // The ears are built (their FFTs planned: a fast ear without FFTW wisdom measures for
  // 0.1-0.3 s of CPU, seconds on a loaded machine) before anything can be sent: built in the
  // listening thread, they came up after the first frames had gone out, and those frames'
  // answers, heard while the ear caught up, came after their deadlines. Every robot's links
  // listen: each takes only its own robot's answers (link::Link::answers).
  ears_ = std::make_unique<ReplyListeners>(every_link);
  if (options_.listen_before_talk) {
    const auto seed = options_.backoff_seed.value_or(
        static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
    air_.emplace(answer_silence_ms(), seed);
  }
  worker_ = std::thread([this] { run(); });
  listener_ = std::thread([this] { listen(); });
}

Transmitter::~Transmitter() { shutdown(); }

double Transmitter::now_ms() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - epoch_).count();
}

link::Link& Transmitter::link_for(const LinkProfile& profile, RobotIndex robot) const {
  const Robot& r = robots_.at(robot);
  for (const auto& l : r.owned_links) {
    if (&l->profile() == &profile && std::find(r.links.begin(), r.links.end(), l.get()) != r.links.end()) return *l;
  }
  throw std::invalid_argument("profile " + profile.name + " needs " + std::to_string(profile.sample_rate_hz) +
                              " Hz audio and this server's devices run at " + std::to_string(profile_.sample_rate_hz) +
                              " Hz, or the server was not given it");
}

const link::Link& Transmitter::link_of(const LinkProfile& profile, RobotIndex robot) const {
  return link_for(profile, robot);
}

RobotIndex Transmitter::robot_named(std::string_view name) const {
  std::vector<std::string> names;
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    if (robots_[r].name == name) return r;
    names.push_back(robots_[r].name);
  }
  if (name.empty() && robots_.size() == 1) return 0;
  if (name.empty())
    throw std::invalid_argument("this server drives " + std::to_string(robots_.size()) + " robots (" + names_of(names) +
                                "): name one");
  throw std::invalid_argument("no robot called \"" + std::string(name) + "\": this server drives " + names_of(names) +
                              " (dtmfctl robots)");
}

RobotIndex Transmitter::robot_of(const link::Link& link) const {
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    for (const link::Link* l : robots_[r].links) {
      if (l == &link) return r;
    }
  }
  throw std::logic_error("a link of no robot");
}

std::vector<RobotStatus> Transmitter::robots() const {
  std::vector<RobotStatus> all;
  std::lock_guard lock(mutex_);
  for (const Robot& r : robots_) {
    const link::LinkOptions& o = r.links.front()->options();
    RobotStatus s{r.name, o.address, o.key ? o.key->id_hex() : "", r.model.name, std::nullopt};
    if (r.last_answered_ms) s.last_answered = wall(*r.last_answered_ms);
    all.push_back(std::move(s));
  }
  return all;
}

const link::Link& Transmitter::authenticated_link(RobotIndex robot) const {
  for (const link::Link* l : robots_.at(robot).links) {
    if (l->keyed() && l->can_authenticate()) return *l;
  }
  throw std::invalid_argument("no profile of this sender carries a MAC at " + std::to_string(profile_.sample_rate_hz) +
                              " Hz");
}

const LinkProfile& Transmitter::sendable_profile(const LinkProfile* requested, bool stop, RobotIndex robot) const {
  const LinkProfile& profile = requested ? usable_profile(requested->name) : profile_;
  const link::Link& link = link_for(profile, robot);
  if (robots_.size() > 1 && !link.addresses_robots())
    throw std::invalid_argument(unaddressed(profile.name) + ": send with " + profile_.name);
  if (!link.keyed() || link.can_authenticate()) return profile;
  // A Stop must reach a keyed robot, which refuses frames without a MAC.
  if (stop) return authenticated_link(robot).profile();
  if (options_.allow_unauthenticated) return profile;
  throw UnauthenticatedRefused("profile " + profile.name +
                               " carries no MAC, and this sender has a key: a keyed robot refuses its frames, and "
                               "anyone within earshot can play its ACK. Send with profile " +
                               authenticated_link(robot).name() +
                               ", or start dtmf-server with --allow-unauthenticated-commands");
}

const LinkProfile& Transmitter::usable_profile(std::string_view name) const {
  const LinkProfile& p = profile_by_name(name);
  link_for(p);
  return p;
}

std::shared_ptr<Job> Transmitter::submit(const command::Command& command, Policy policy,
                                         std::chrono::milliseconds decision_timeout, bool to_front,
                                         const LinkProfile* profile, RobotIndex robot) {
  link::Link& link = link_for(sendable_profile(profile, std::holds_alternative<command::Stop>(command), robot), robot);
  return enqueue(link, command, policy, decision_timeout, to_front);
}

std::shared_ptr<Job> Transmitter::enqueue(link::Link& link, const command::Command& command, Policy policy,
                                          std::chrono::milliseconds decision_timeout, bool to_front) {
  std::shared_ptr<Job> job;
  std::vector<std::shared_ptr<Job>> overtaken;
  const bool stop = std::holds_alternative<command::Stop>(command);
  {
    std::lock_guard lock(mutex_);
    job = std::make_shared<Job>(link, command, policy, decision_timeout, run_id_);
    if (!command::every_robot(command)) job->set_robot(robots_[robot_of(link)].name);
    if (stopping_) throw TransmitterUnavailable("the server is shutting down");
    if (!unavailable_.empty()) throw TransmitterUnavailable(unavailable_);
    // A stop is never refused for a full queue: it goes first, and what it stops waits behind it.
    if (queue_.size() >= options_.max_queue && !stop) {
      throw QueueFull("the transmit queue is full (" + std::to_string(options_.max_queue) +
                      " commands wait); retry later, or send Stop, which goes first");
    }
    if (stop) overtaken = stop_overtakes(link, command);
    // Queued is emitted before the worker can see the job, so that it comes first.
    ProgressEvent queued{Kind::Queued};
    queued.frame_count = job->frame_count();
    queued.queue_position = (to_front ? 0 : static_cast<int>(queue_.size())) + (on_air_ ? 1 : 0);
    emit(*job, queued);
    if (to_front)
      queue_.push_front(job);
    else
      queue_.push_back(job);
  }
  for (const auto& o : overtaken) o->overtake();  // outside the lock: a job's own lock comes after ours
  changed_.notify_all();
  return job;
}

bool Transmitter::decide(const std::string& command_id, reliability::Decision decision) {
  std::shared_ptr<Job> job;
  {
    std::lock_guard lock(mutex_);
    if (on_air_ && on_air_->id() == command_id) job = on_air_;
  }
  return job && job->decide(decision);
}

void Transmitter::set_run(std::optional<std::string> run_id) {
  std::lock_guard lock(mutex_);
  run_id_ = std::move(run_id);
}

}  // namespace dtmf::server
