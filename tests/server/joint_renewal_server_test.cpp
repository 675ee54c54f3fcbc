// Joint renewals through the whole sender (docs/protocol.md §10, "Renewing leases together"):
// three robots, keyed or not, driven live at once, each by its own Teleop stream, in one simulated
// room. The transmitter renews their leases together, one unanswered frame for all three,
// more than twice a second; each robot's cmd_vel never comes to a standstill while its
// stream holds a target, and no robot executes another's velocity. A stream that ends, and a
// Stop, end that robot's renewals, and only that robot's.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <thread>

#include "command/command.h"
#include "fleet_system.h"
#include "teleop_client.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::FleetKeys;
using test_support::FleetSystem;
using test_support::TeleopClient;

namespace {

test_support::FleetOptions three_robots(FleetKeys keys) {
  test_support::FleetOptions o;
  o.names = {"robot1", "robot2", "robot3"};
  o.positions_m = {1.0, 2.0, 3.0};
  o.keys = keys;
  return o;
}

// How often the robot came to a standstill on cmd_vel since `from`.
int standstills_since(test_support::FleetRobot& robot, std::chrono::steady_clock::time_point from) {
  int n = 0;
  bool was_moving = true;
  for (const auto& s : robot.samples()) {
    const bool moving = s.velocity.linear_mps != 0 || s.velocity.angular_radps != 0;
    if (s.at >= from && was_moving && !moving) ++n;
    was_moving = moving;
  }
  return n;
}

}  // namespace

class ServerJointRenewal : public ::testing::TestWithParam<FleetKeys> {};

// With keys, sealed renewals (reliability/renewal_frame.h); without, plain ones
// (reliability/plain_renewal.h): until 2026-11-30 three unkeyed streams renewed each lease
// with frames of their own, 1.92 times a second, and a lease ran out now and then.
TEST_P(ServerJointRenewal, ThreeStreamsAreRenewedTogetherAndNoLeaseRunsOut) {
  FleetSystem fleet(three_robots(GetParam()));
  const std::array<double, 3> linear{0.05, 0.1, 0.15};
  std::array<std::unique_ptr<TeleopClient>, 3> streams;
  for (std::size_t k = 0; k < 3; ++k)
    streams[k] = std::make_unique<TeleopClient>(fleet.stub(), linear[k], 0.0, 1.0, "fast", fleet.name(k));
  for (std::size_t k = 0; k < 3; ++k) ASSERT_TRUE(streams[k]->confirmed(linear[k], 0, 20s)) << fleet.name(k);

  std::array<int, 3> renewals_before{};
  std::array<std::size_t, 3> executed_before{};
  for (std::size_t k = 0; k < 3; ++k) {
    renewals_before[k] = fleet.robot(k).renewals();
    executed_before[k] = fleet.robot(k).executed().size();
  }
  const auto from = std::chrono::steady_clock::now();
  constexpr double kDriven_s = 5.0;
  std::this_thread::sleep_for(std::chrono::duration<double>(kDriven_s));
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(fleet.name(k));
    const int renewed = fleet.robot(k).renewals() - renewals_before[k];
    const auto executed = fleet.robot(k).executed();
    const auto frames = static_cast<int>(executed.size() - executed_before[k]);
    // Every 400 ms: about 12 in 5 s; its own frames only to check the link (every 5 s).
    EXPECT_GE(renewed, static_cast<int>(2 * kDriven_s)) << "renewed " << renewed << " times in " << kDriven_s << " s";
    EXPECT_LE(frames - renewed, 2) << "velocity frames of its own, besides the renewals";
    EXPECT_EQ(standstills_since(fleet.robot(k), from), 0) << "a lease ran out while its stream held a target";
    for (std::size_t i = executed_before[k]; i < executed.size(); ++i) {
      const auto& v = std::get<command::Velocity>(executed[i].second);
      EXPECT_GT(v.linear_fraction, 0.0);
    }
  }

  // robot2's client leaves: its renewals end, and it stands within its lease; the others go on.
  EXPECT_TRUE(streams[1]->close().ok());
  const auto closed = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(1500ms);
  const auto standing = fleet.robot(1).standing_since();
  ASSERT_TRUE(standing) << "robot2 still moves 1.5 s after its stream ended";
  EXPECT_LT(*standing - closed, 1300ms) << "more than its lease (1 s) and a frame after the stream ended";
  const int robot2_renewals = fleet.robot(1).renewals();
  const int robot1_renewals = fleet.robot(0).renewals();
  std::this_thread::sleep_for(1s);
  EXPECT_EQ(fleet.robot(1).renewals(), robot2_renewals) << "renewed after its stream ended";
  EXPECT_GT(fleet.robot(0).renewals(), robot1_renewals) << "robot1's renewals ended with robot2's stream";
  EXPECT_FALSE(fleet.robot(0).standing_since());
  EXPECT_FALSE(fleet.robot(2).standing_since());
  EXPECT_TRUE(streams[0]->close().ok());
  EXPECT_TRUE(streams[2]->close().ok());
}

INSTANTIATE_TEST_SUITE_P(Keys, ServerJointRenewal, ::testing::Values(FleetKeys::OwnAndRoom, FleetKeys::None),
                         [](const auto& param_info) {
                           return param_info.param == FleetKeys::None ? "Unkeyed" : "Keyed";
                         });
