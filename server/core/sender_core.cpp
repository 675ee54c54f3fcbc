// SenderCore: its robots, its profiles, and what it tells of them.
#include "sender_core.h"

#include <algorithm>
#include <chrono>

namespace dtmf::server {

namespace {

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

SenderCore::SenderCore(std::vector<RobotLinks> robots, const LinkProfile& profile, TransmitterOptions options,
                       std::vector<std::unique_ptr<link::Link>> room_links)
    : profile_(profile),
      options_(std::move(options)),
      room_links_(room_links.empty() ? link::make_links({}) : std::move(room_links)) {
  if (robots.empty()) throw std::invalid_argument("a sender needs a robot to drive");
  for (RobotLinks& given : robots) add_robot(std::move(given));
  for (RobotIndex r = 0; r < robots_.size(); ++r) check_default_profile(r);
  if (options_.listen_before_talk) {
    // The seed: a number no clock of the core's own gives; the driver passes one, or the
    // steady clock's reading at construction when it passes none (transmitter.h).
    air_.emplace(answer_silence_ms(), options_.backoff_seed.value_or(1));
  }
}

void SenderCore::add_robot(RobotLinks given) {
  Robot robot{std::move(given.name), std::move(given.model), std::move(given.links), {}, {}, {}, nullptr, {}, {}};
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
  robots_.push_back(std::move(robot));
}

// The default profile must be among each robot's links, and with a key carry a MAC; with
// several robots, name the robot.
void SenderCore::check_default_profile(RobotIndex r) const {
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

std::vector<const link::Link*> SenderCore::every_link() const {
  std::vector<const link::Link*> all;
  for (const Robot& r : robots_) all.insert(all.end(), r.links.begin(), r.links.end());
  return all;
}

link::Link& SenderCore::link_for(const LinkProfile& profile, RobotIndex robot) const {
  const Robot& r = robots_.at(robot);
  for (const auto& l : r.owned_links) {
    if (&l->profile() == &profile && std::find(r.links.begin(), r.links.end(), l.get()) != r.links.end()) return *l;
  }
  throw std::invalid_argument("profile " + profile.name + " needs " + std::to_string(profile.sample_rate_hz) +
                              " Hz audio and this server's devices run at " + std::to_string(profile_.sample_rate_hz) +
                              " Hz, or the server was not given it");
}

RobotIndex SenderCore::robot_named(std::string_view name) const {
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

RobotIndex SenderCore::robot_of(const link::Link& link) const {
  for (RobotIndex r = 0; r < robots_.size(); ++r) {
    for (const link::Link* l : robots_[r].links) {
      if (l == &link) return r;
    }
  }
  throw std::logic_error("a link of no robot");
}

const link::Link& SenderCore::authenticated_link(RobotIndex robot) const {
  for (const link::Link* l : robots_.at(robot).links) {
    if (l->keyed() && l->can_authenticate()) return *l;
  }
  throw std::invalid_argument("no profile of this sender carries a MAC at " + std::to_string(profile_.sample_rate_hz) +
                              " Hz");
}

const LinkProfile& SenderCore::sendable_profile(const LinkProfile* requested, bool stop, RobotIndex robot) const {
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

const LinkProfile& SenderCore::usable_profile(std::string_view name) const {
  const LinkProfile& p = profile_by_name(name);
  link_for(p);
  return p;
}

AirShare SenderCore::air_share() const {
  AirShare share;
  share.busy_blocks = carrier_.busy_blocks();
  share.others_answers = carrier_.others_answers();
  share.masked_answers = carrier_.masked_answers();
  if (air_) {
    share.deferred = air_->deferred();
    share.answered_waits = air_->answered_waits();
    share.yields = air_->yields();
    share.listens = air_->listens();
  }
  return share;
}

double SenderCore::answer_silence_ms() const {
  double longest = 0;
  const auto consider = [&longest](const link::Link& l) {
    longest = std::max(longest, l.profile().timing.ack_timeout_ms - l.profile().timing.chord_ms);
  };
  for (const Robot& r : robots_)
    for (const link::Link* l : r.links) consider(*l);
  for (const auto& l : room_links_) consider(*l);
  return longest;
}

}  // namespace dtmf::server
