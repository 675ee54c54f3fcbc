#include "fleet_system.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <stdexcept>

#include "security/counter_clock.h"
#include "security/counter_store.h"

namespace dtmf::test_support {

namespace {

const LinkProfile& fast() { return profile_by_name("fast"); }

store::StoreOptions no_database() {
  store::StoreOptions none;
  none.database = std::string();
  return none;
}

sim::ChannelConfig air_of(const FleetOptions& o) {
  sim::ChannelConfig air;
  air.noise = o.rir_file.empty() ? sim::parse_noise("white", -70) : sim::parse_noise("pink", -50);
  air.room.rir_file = o.rir_file;
  return air;
}

// Robot `address`'s options, the sender's side or the robot's, with fresh counters each.
link::LinkOptions keyed_at(std::uint8_t address, const FleetOptions& o, bool robot_side) {
  link::LinkOptions l;
  l.address = address;
  l.first_sequence = o.first_sequence;
  if (robot_side) l.wall_clock = [offset = o.robot_clock_offset] { return std::chrono::system_clock::now() + offset; };
  if (o.keys == FleetKeys::None) return l;
  l.key = fleet_key(address);
  // Counters that name today, as a sender's do (security/counter_clock.h).
  const std::uint64_t today = security::clock_counter_floor(std::chrono::system_clock::now());
  l.counters = robot_side ? std::make_shared<security::MemoryCounterStore>(1, 0)
                          : std::make_shared<security::MemoryCounterStore>(today);
  if (o.keys == FleetKeys::OwnAndRoom && robot_side) {
    l.room_key = fleet_key(kRoomKeySeed);
    l.room_counters = std::make_shared<security::MemoryCounterStore>(1, o.robot_room_kept);
  }
  return l;
}

const command::RobotModel& model_of(std::size_t k) { return k == 1 ? command::waffle() : command::burger(); }

}  // namespace

std::shared_ptr<const security::LinkKey> fleet_key(unsigned char seed) {
  std::array<unsigned char, security::kKeyBytes> bytes{};
  bytes.fill(seed);
  return security::LinkKey::from_bytes(bytes);
}

FleetRobot::FleetRobot(sim::SimulatedAir::Station station, link::LinkOptions link, const command::RobotModel& model)
    : microphone_(std::move(station.microphone)),
      replies_(std::move(station.speaker), std::chrono::milliseconds(0)),
      store_(no_database()),
      timeline_(true) {
  agent::AgentOptions options;
  options.profiles = {&fast()};
  options.link = std::move(link);
  options.model = model;
  options.on_frame_heard = [this](const agent::HeardFrame& frame) {
    if (!frame.executed) return;
    std::lock_guard lock(mutex_);
    if (frame.reception.event == link::ReceptionEvent::Renewed) ++renewals_;
    executed_.emplace_back(std::chrono::steady_clock::now(), *frame.executed);
  };
  agent_ =
      std::make_unique<agent::Agent>(options, replies_, std::vector<agent::CmdVelOutput*>{this}, store_, timeline_);
  thread_ = std::thread([this] {
    std::vector<float> block(static_cast<std::size_t>(agent_->block_samples()));
    while (const std::size_t got = microphone_->read(block)) agent_->process(std::span<const float>(block.data(), got));
  });
}

FleetRobot::~FleetRobot() { thread_.join(); }

void FleetRobot::publish(const agent::Velocity& v, double, std::chrono::system_clock::time_point) {
  std::lock_guard lock(mutex_);
  const bool moving = v.linear_mps != 0 || v.angular_radps != 0;
  const auto now = std::chrono::steady_clock::now();
  if (moving_ && !moving) stopped_at_ = now;
  moving_ = moving;
  moved_ = moved_ || moving;
  samples_.push_back({now, v});
}

bool FleetRobot::moved() {
  std::lock_guard lock(mutex_);
  return moved_;
}

std::optional<std::chrono::steady_clock::time_point> FleetRobot::standing_since() {
  std::lock_guard lock(mutex_);
  return moving_ ? std::nullopt : stopped_at_;
}

std::vector<std::pair<std::chrono::steady_clock::time_point, command::Command>> FleetRobot::executed() {
  std::lock_guard lock(mutex_);
  return executed_;
}

int FleetRobot::renewals() {
  std::lock_guard lock(mutex_);
  return renewals_;
}

std::vector<VelocitySample> FleetRobot::samples(std::size_t from) {
  std::lock_guard lock(mutex_);
  return {samples_.begin() + static_cast<long>(std::min(from, samples_.size())), samples_.end()};
}

FleetSystem::FleetSystem(FleetOptions options)
    : options_(std::move(options)), air_(fast().sample_rate_hz, air_of(options_), 10) {
  if (options_.names.size() != options_.positions_m.size() || options_.names.empty() || options_.names.size() > 7)
    throw std::invalid_argument("a fleet of 1 to 7 robots, each with a name and a position");
  auto sender = air_.add_station("sender", 0.0);
  std::vector<sim::SimulatedAir::Station> stations;
  for (std::size_t k = 0; k < options_.names.size(); ++k)
    stations.push_back(air_.add_station(options_.names[k], options_.positions_m[k]));
  if (options_.stranger_m) stranger_ = air_.add_station("stranger", *options_.stranger_m);
  air_.start();
  for (std::size_t k = 0; k < stations.size(); ++k)
    robots_.push_back(std::make_unique<FleetRobot>(
        std::move(stations[k]), keyed_at(static_cast<std::uint8_t>(k + 1), options_, true), model_of(k)));
  store::StoreOptions none = no_database();
  none.spill_path = ::testing::TempDir() + "/fleet-system-" + std::to_string(::getpid()) + ".spill";
  store_ = std::make_unique<store::Store>(none);
  recorder_ = std::make_unique<server::StoreRecorder>(*store_, "test");
  std::vector<server::RobotLinks> robots(options_.names.size());
  for (std::size_t k = 0; k < robots.size(); ++k) {
    robots[k].name = options_.names[k];
    robots[k].links = link::make_links(keyed_at(static_cast<std::uint8_t>(k + 1), options_, false));
  }
  for (std::size_t k = 0; k < robots.size(); ++k) robots[k].model = model_of(k);
  link::LinkOptions room;
  if (options_.keys == FleetKeys::OwnAndRoom) {
    room.key = fleet_key(kRoomKeySeed);
    room.counters = std::make_shared<security::MemoryCounterStore>(
        security::clock_counter_floor(std::chrono::system_clock::now() + options_.room_clock_offset));
  }
  server::TransmitterOptions transmitter;
  transmitter.max_queue = options_.max_queue;
  transmitter_ = std::make_unique<server::Transmitter>(std::move(robots), fast(), std::move(sender.speaker),
                                                       std::move(sender.microphone), *recorder_, transmitter,
                                                       link::make_links(room));
  service_ = std::make_unique<server::TeleopService>(*transmitter_, *store_, server::ServiceOptions{});
  grpc::ServerBuilder builder;
  builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port_);
  builder.RegisterService(service_.get());
  server_ = builder.BuildAndStart();
  stub_ = v1::TeleopService::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port_), grpc::InsecureChannelCredentials()));
}

FleetSystem::~FleetSystem() {
  transmitter_->shutdown();
  server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  air_.stop();
  robots_.clear();
}

}  // namespace dtmf::test_support
