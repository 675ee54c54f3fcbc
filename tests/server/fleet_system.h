// Test and benchmark fixture: one sender and several robots, the whole system in one
// process. A transmitter drives robots robot1..robotN (addresses 1..N) through one
// loudspeaker; N robot agents listen in one simulated room (sim/simulated_air.h: every
// microphone hears every loudspeaker, each path at its own distance), with a measured room
// both ways if given; real gRPC on loopback. Each robot keeps every cmd_vel sample it
// publishes, with the time, for the caller to read.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "agent.h"
#include "dtmf/v1/teleop.grpc.pb.h"
#include "security/link_key.h"
#include "sim/simulated_air.h"
#include "store_recorder.h"
#include "teleop_service.h"

namespace dtmf::test_support {

// Which keys the fleet holds: none; each robot its own; each its own and the room key.
enum class FleetKeys { None, Own, OwnAndRoom };

// The second robot is a Waffle, the others Burgers (sender and agent alike).
struct FleetOptions {
  std::vector<std::string> names = {"alpha", "beta"};  // robot k (from 1) is at address k
  std::vector<double> positions_m = {1.0, 1.5};        // each robot's distance from the sender
  FleetKeys keys = FleetKeys::None;
  std::string rir_file;             // a measured room (pink noise -50 dBFS); empty: free field, white -70 dBFS
  std::uint8_t first_sequence = 0;  // every sender link's: so that robots' numbers collide
  // Faults a stop must get through (stop_always_server_test.cpp):
  std::chrono::seconds robot_clock_offset{0};  // each robot's wall clock against the sender's
  std::uint64_t robot_room_kept = 0;           // the newest room counter each robot kept
  std::chrono::seconds room_clock_offset{0};   // the clock the sender's room counters follow
  std::size_t max_queue = 32;                  // the transmitter's queue
  std::optional<double> stranger_m;            // a station with a loudspeaker of its own, this far out
};

// One cmd_vel sample a robot published, and when.
struct VelocitySample {
  std::chrono::steady_clock::time_point at;
  agent::Velocity velocity;
};

// A robot agent on a station of the air.
class FleetRobot : public agent::CmdVelOutput {
 public:
  FleetRobot(sim::SimulatedAir::Station station, link::LinkOptions link, const command::RobotModel& model);
  ~FleetRobot() override;  // the air stopped: the microphone ends

  void publish(const agent::Velocity& v, double, std::chrono::system_clock::time_point) override;
  bool moved();
  // When it last came to a standstill (it was moving, and published zero), if it is still.
  std::optional<std::chrono::steady_clock::time_point> standing_since();
  std::vector<VelocitySample> samples(std::size_t from = 0);
  // When the agent executed each command it took (a Velocity's renewal counts), and what.
  std::vector<std::pair<std::chrono::steady_clock::time_point, command::Command>> executed();
  // How many of those were joint renewals (link::ReceptionEvent::Renewed).
  int renewals();

 private:
  std::unique_ptr<physical::AudioSource> microphone_;
  agent::LiveReplyPlayer replies_;
  store::Store store_;
  agent::Timeline timeline_;
  std::unique_ptr<agent::Agent> agent_;
  std::thread thread_;
  std::mutex mutex_;
  bool moved_ = false, moving_ = false;
  int renewals_ = 0;
  std::optional<std::chrono::steady_clock::time_point> stopped_at_;
  std::vector<VelocitySample> samples_;
  std::vector<std::pair<std::chrono::steady_clock::time_point, command::Command>> executed_;
};

class FleetSystem {
 public:
  explicit FleetSystem(FleetOptions options = {});
  ~FleetSystem();

  v1::TeleopService::Stub& stub() { return *stub_; }
  FleetRobot& robot(std::size_t k) { return *robots_.at(k); }  // from 0
  std::size_t size() const { return robots_.size(); }
  const std::string& name(std::size_t k) const { return options_.names.at(k); }
  // A station's loudspeaker silenced (its answers lost), or sounding again.
  void mute(const std::string& station, bool muted) { air_.mute(station, muted); }
  // The stranger's loudspeaker (FleetOptions::stranger_m): what it plays, everyone hears.
  physical::AudioSink& stranger() { return *stranger_.speaker; }
  // What the sender heard of others on the air, and how often it waited for them.
  server::AirShare air_share() const { return transmitter_->air_share(); }

 private:
  FleetOptions options_;
  sim::SimulatedAir air_;
  sim::SimulatedAir::Station stranger_;
  std::vector<std::unique_ptr<FleetRobot>> robots_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<server::StoreRecorder> recorder_;
  std::unique_ptr<server::Transmitter> transmitter_;
  std::unique_ptr<server::TeleopService> service_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
  std::unique_ptr<v1::TeleopService::Stub> stub_;
};

// The fleet's test keys: robot k's own (k from 1), and the room key.
std::shared_ptr<const security::LinkKey> fleet_key(unsigned char seed);
inline constexpr unsigned char kRoomKeySeed = 0x99;

}  // namespace dtmf::test_support
