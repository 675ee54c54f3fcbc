// One sender, several robots: the whole system in one process. A transmitter that drives
// robots "alpha" (address 1) and "beta" (address 2) through one loudspeaker, two robot
// agents listening in one simulated room (each hearing the sender, the other robot and
// itself), and real gRPC on loopback. A command names its robot; only that robot moves, and
// only its answer confirms the command. Both sides start at the same sequence number, so
// every frame's number collides with the other robot's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <thread>

#include "agent.h"
#include "fleet_system.h"
#include "live_system.h"
#include "security/link_key.h"
#include "sim/simulated_air.h"
#include "support/wait_for.h"
#include "teleop_client.h"
#include "teleop_service.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::read_stream;
using test_support::TeleopClient;
using test_support::wait_until;

namespace {

const LinkProfile& fast = profile_by_name("fast");

link::LinkOptions at(std::uint8_t address) {
  link::LinkOptions o;
  o.address = address;
  o.first_sequence = 0;
  return o;
}

using test_support::FleetKeys;
using Robot = test_support::FleetRobot;

// Robots alpha (address 1, 1 m from the sender) and beta (address 2, 1.5 m), beta a Waffle.
class Fleet : public test_support::FleetSystem {
 public:
  explicit Fleet(FleetKeys keys = FleetKeys::None) : FleetSystem(options(keys)) {}

  test_support::StreamResult<v1::DriveResponse> drive(const std::string& robot) {
    v1::DriveRequest r;
    r.set_speed_percent(30);
    r.set_duration_s(1);
    r.mutable_options()->set_robot(robot);
    r.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_FAIL);
    return read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return stub().Drive(&c, r); });
  }
  v1::ListRobotsResponse robots() {
    grpc::ClientContext c;
    v1::ListRobotsResponse response;
    EXPECT_TRUE(stub().ListRobots(&c, {}, &response).ok());
    return response;
  }
  Robot& alpha() { return robot(0); }
  Robot& beta() { return robot(1); }

 private:
  static test_support::FleetOptions options(FleetKeys keys) {
    test_support::FleetOptions o;
    o.keys = keys;
    return o;
  }
};

}  // namespace

TEST(ServerFleet, ACommandMovesOnlyTheRobotItNamesAndOnlyItsAnswerConfirmsIt) {
  Fleet fleet;
  const auto to_beta = fleet.drive("beta");
  ASSERT_TRUE(to_beta.status.ok()) << to_beta.status.error_message();
  EXPECT_EQ(to_beta.responses.back().progress().event(), v1::FRAME_EVENT_CONFIRMED);
  EXPECT_EQ(to_beta.responses.back().progress().robot(), "beta");
  // Confirmed at its first transmission: beta's answer, and no other, was taken.
  EXPECT_EQ(std::count_if(to_beta.responses.begin(), to_beta.responses.end(),
                          [](const auto& r) { return r.progress().event() == v1::FRAME_EVENT_TRANSMITTING; }),
            1);
  std::this_thread::sleep_for(300ms);  // alpha heard the same frame: it must not have moved
  EXPECT_TRUE(fleet.beta().moved());
  EXPECT_FALSE(fleet.alpha().moved()) << "robot alpha executed beta's frame";

  // Alpha's first frame carries the same sequence number beta's did (both links start at 0).
  const auto to_alpha = fleet.drive("alpha");
  ASSERT_TRUE(to_alpha.status.ok()) << to_alpha.status.error_message();
  EXPECT_EQ(to_alpha.responses.back().progress().sequence(), to_beta.responses.back().progress().sequence());
  EXPECT_TRUE(fleet.alpha().moved());

  const auto robots = fleet.robots();
  ASSERT_EQ(robots.robots_size(), 2);
  EXPECT_EQ(robots.robots(0).name(), "alpha");
  EXPECT_EQ(robots.robots(0).address(), 1u);
  EXPECT_EQ(robots.robots(1).name(), "beta");
  EXPECT_EQ(robots.robots(1).address(), 2u);
  EXPECT_EQ(robots.robots(1).model(), "waffle");
  EXPECT_GT(robots.robots(0).last_answered_unix_ms(), 0);
  EXPECT_GE(robots.robots(0).last_answered_unix_ms(), robots.robots(1).last_answered_unix_ms())
      << "alpha answered last";
}

TEST(ServerFleet, AnUnknownOrMissingRobotNameIsInvalidArgumentNamingTheRobots) {
  Fleet fleet;
  for (const std::string name : {"gamma", ""}) {
    const auto r = fleet.drive(name);
    EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << "\"" << name << "\"";
    EXPECT_NE(r.status.error_message().find("options.robot"), std::string::npos) << r.status.error_message();
    EXPECT_NE(r.status.error_message().find("alpha, beta"), std::string::npos) << r.status.error_message();
  }
  EXPECT_FALSE(fleet.alpha().moved());
  EXPECT_FALSE(fleet.beta().moved());
  const v1::ListRobotsResponse robots = fleet.robots();
  for (const auto& robot : robots.robots()) EXPECT_EQ(robot.last_answered_unix_ms(), 0) << robot.name();
}

TEST(ServerFleet, AProfileWhoseFramesNameNoRobotIsRefusedAmongSeveral) {
  Fleet fleet;
  v1::DriveRequest r;
  r.set_speed_percent(30);
  r.mutable_options()->set_robot("alpha");
  r.mutable_options()->set_profile("seed");
  const auto refused =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return fleet.stub().Drive(&c, r); });
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(refused.status.error_message().find("options.profile: profile seed names no robot"), std::string::npos)
      << refused.status.error_message();
  EXPECT_FALSE(fleet.alpha().moved());
  EXPECT_FALSE(fleet.beta().moved());
}

TEST(ServerFleet, EachRobotHasItsOwnTeleopStreamAndAStopEndsOnlyItsRobots) {
  Fleet fleet;
  TeleopClient alpha(fleet.stub(), 0.1, 0, 1.0, "fast", "alpha");
  TeleopClient beta(fleet.stub(), 0.05, 0, 1.0, "fast", "beta");
  ASSERT_TRUE(alpha.confirmed(0.1, 0, 10s)) << "alpha's stream drove nothing";
  ASSERT_TRUE(beta.confirmed(0.05, 0, 10s)) << "beta's stream drove nothing";
  EXPECT_TRUE(fleet.alpha().moved());
  EXPECT_TRUE(fleet.beta().moved());

  // One stream drives a robot at a time: a second one to alpha, and a Drive to alpha, are
  // refused naming alpha.
  {
    TeleopClient again(fleet.stub(), 0.02, 0, 1.0, "fast", "alpha");
    EXPECT_TRUE(again.ended(5s));
    const grpc::Status status = again.finish();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
    EXPECT_NE(status.error_message().find("the robot (alpha)"), std::string::npos) << status.error_message();
  }
  const auto drive = fleet.drive("alpha");
  EXPECT_EQ(drive.status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(drive.status.error_message().find("the robot (alpha)"), std::string::npos) << drive.status.error_message();

  // Stop to beta ends beta's stream; alpha's goes on.
  v1::StopRequest stop;
  stop.mutable_options()->set_robot("beta");
  const auto stopped =
      read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return fleet.stub().Stop(&c, stop); });
  EXPECT_TRUE(stopped.status.ok()) << stopped.status.error_message();
  EXPECT_TRUE(beta.ended(5s));
  EXPECT_EQ(beta.finish().error_code(), grpc::StatusCode::ABORTED);
  alpha.target(0.12, 0);
  EXPECT_TRUE(alpha.confirmed(0.12, 0, 10s)) << "alpha's stream ended with beta's";
  EXPECT_TRUE(alpha.close().ok());
}

TEST(ServerFleet, AStopForEveryRobotStopsThemAllAtOnceAndEndsEveryStream) {
  for (const FleetKeys keys : {FleetKeys::None, FleetKeys::OwnAndRoom}) {
    SCOPED_TRACE(keys == FleetKeys::None ? "no keys" : "own keys and the room key");
    Fleet fleet(keys);
    // Leases of 2 s, renewed every second: a robot that stops within 300 ms of the stop's
    // first copy was stopped by it, not by a lease.
    TeleopClient alpha(fleet.stub(), 0.1, 0, 2.0, "fast", "alpha");
    TeleopClient beta(fleet.stub(), 0.05, 0, 2.0, "fast", "beta");
    ASSERT_TRUE(alpha.confirmed(0.1, 0, 10s)) << "alpha's stream drove nothing";
    ASSERT_TRUE(beta.confirmed(0.05, 0, 10s)) << "beta's stream drove nothing";
    // The ACK sounds as the robot decides; its cmd_vel follows on its next publication (within
    // 50 ms), which the sender's hearing the ACK can precede.
    ASSERT_TRUE(wait_until([&] { return fleet.alpha().moved() && fleet.beta().moved(); }, 1s));

    v1::StopRequest stop;
    stop.set_all_robots(true);
    const auto stopped =
        read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return fleet.stub().Stop(&c, stop); });
    ASSERT_TRUE(stopped.status.ok()) << stopped.status.error_message();
    const v1::Progress& last = stopped.responses.back().progress();
    EXPECT_EQ(last.event(), v1::FRAME_EVENT_SENT);
    EXPECT_EQ(last.robot(), "");
    EXPECT_EQ(last.command(), "stop every_robot");
    std::optional<std::chrono::system_clock::time_point> first_copy;
    int copies = 0;
    for (const auto& r : stopped.responses) {
      EXPECT_NE(r.progress().event(), v1::FRAME_EVENT_ACK) << "a stop for every robot was answered";
      if (r.progress().event() != v1::FRAME_EVENT_TRANSMITTING) continue;
      ++copies;
      EXPECT_EQ(r.progress().authenticated(), keys != FleetKeys::None);
      if (!first_copy)
        first_copy = std::chrono::system_clock::time_point(std::chrono::milliseconds(r.progress().time_unix_ms()));
    }
    EXPECT_EQ(copies, 2);
    const auto sent_steady = std::chrono::steady_clock::now() - (std::chrono::system_clock::now() - *first_copy);
    EXPECT_TRUE(alpha.ended(5s));
    EXPECT_TRUE(beta.ended(5s));
    EXPECT_EQ(alpha.finish().error_code(), grpc::StatusCode::ABORTED);
    EXPECT_EQ(beta.finish().error_code(), grpc::StatusCode::ABORTED);
    for (Robot* robot : {&fleet.alpha(), &fleet.beta()}) {
      const auto still = robot->standing_since();
      ASSERT_TRUE(still.has_value()) << "a robot still moves";
      const double after_ms = std::chrono::duration<double, std::milli>(*still - sent_steady).count();
      std::printf("stopped %.0f ms after the stop's first copy began\n", after_ms);
      EXPECT_LT(after_ms, 300.0) << "stopped by its lease, not by the stop";
    }
  }
}

TEST(ServerFleet, KeyedRobotsTakeAStopForEveryRobotOnlyUnderTheRoomKey) {
  Fleet fleet(FleetKeys::Own);
  v1::StopRequest stop;
  stop.set_all_robots(true);
  const auto refused =
      read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return fleet.stub().Stop(&c, stop); });
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(refused.status.error_message().find("dtmf-server --room-key"), std::string::npos)
      << refused.status.error_message();
  stop.mutable_options()->set_robot("alpha");
  const auto named = read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return fleet.stub().Stop(&c, stop); });
  EXPECT_EQ(named.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(named.status.error_message().find("options.robot"), std::string::npos) << named.status.error_message();
}

TEST(ServerFleet, RobotsMustNotShareANameAnAddressOrAKey) {
  struct NullObserver : server::ProgressObserver {
    void observe(const server::Job&, const server::ProgressEvent&) override {}
  } observer;
  std::array<unsigned char, security::kKeyBytes> bytes{};
  bytes.fill(7);
  const auto key = security::LinkKey::from_bytes(bytes);
  const auto two = [&](std::uint8_t b, const std::string& name_b, bool keys) {
    std::vector<server::RobotLinks> robots(2);
    link::LinkOptions first = at(1), second = at(b);
    if (keys) first.key = second.key = key;
    robots[0].name = "alpha";
    robots[0].links = link::make_links(first);
    robots[1].name = name_b;
    robots[1].links = link::make_links(second);
    return robots;
  };
  sim::SimulatedAir air(fast.sample_rate_hz, {}, 10);
  const auto expect_refused = [&](std::vector<server::RobotLinks> robots, const std::string& why) {
    auto station = air.add_station(why, 0);
    try {
      server::Transmitter t(std::move(robots), fast, std::move(station.speaker), std::move(station.microphone),
                            observer, {});
      ADD_FAILURE() << "accepted robots that share " << why;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  expect_refused(two(1, "beta", false), "address 1");
  expect_refused(two(2, "alpha", false), "alpha");
  expect_refused(two(2, "beta", true), "key " + key->id_hex());
}
