// The fast profile through the whole system: real gRPC on loopback, the transmitter, a
// simulated room, the robot agent listening with every profile. A command asks for the
// profile in its options; the server's default stays the seed's.
#include <gtest/gtest.h>

#include "support/wait_for.h"

using namespace std::chrono_literals;
using dtmf::test_support::wait_until;

#include <algorithm>

#include "command/command_payload.h"
#include "link/link.h"
#include "live_system.h"
#include "support/third_profile.h"

using namespace dtmf;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;

namespace {

v1::DriveRequest fast_drive(double speed, double duration_s) {
  v1::DriveRequest r;
  r.set_speed_percent(speed);
  r.set_duration_s(duration_s);
  r.mutable_options()->set_profile("fast");
  return r;
}

}  // namespace

TEST(ServerFast, ADriveIsOneNamedFrameConfirmedAndExecutedWhole) {
  LiveSystem system;
  auto client = system.client();
  const auto result =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, fast_drive(50, 3)); });
  ASSERT_TRUE(result.status.ok()) << result.status.error_message();
  const std::string expected = command::describe(command::quantised_payload(command::DriveForDuration{50, 3}));
  int transmitted = 0, acked = 0;
  std::optional<std::uint32_t> sequence;
  for (const auto& r : result.responses) {
    const v1::Progress& p = r.progress();
    EXPECT_EQ(p.profile(), "fast");
    EXPECT_EQ(p.frame_count(), 1u);
    EXPECT_EQ(p.command(), expected);
    EXPECT_FALSE(p.has_word()) << "a fast frame carries a command, not a word";
    if (p.event() == v1::FRAME_EVENT_TRANSMITTING) {
      ++transmitted;
      EXPECT_EQ(p.frame_bits().size(), 50u);
      EXPECT_EQ(p.tones_hz_size(), 16);
      ASSERT_TRUE(p.has_sequence());
      sequence = p.sequence();
    }
    if (p.event() == v1::FRAME_EVENT_ACK) {
      ++acked;
      EXPECT_GT(p.response_time_ms(), 0);
      EXPECT_LT(p.response_time_ms(), 500);  // the fast profile's ACK timeout
    }
  }
  EXPECT_EQ(result.responses.back().progress().event(), v1::FRAME_EVENT_CONFIRMED);
  EXPECT_EQ(transmitted, 1);
  EXPECT_EQ(acked, 1);
  EXPECT_TRUE(sequence.has_value());
  EXPECT_EQ(system.commands_executed(), std::vector<std::string>{expected});
  EXPECT_TRUE(system.words_heard().empty()) << "no seed word went on air";
  // cmd_vel is published on the agent's next tick (50 ms), which may follow its ACK.
  EXPECT_TRUE(wait_until([&] { return system.last_velocity().linear_mps == 0.11; }, 1s))
      << system.last_velocity().linear_mps;
}

// A profile the server, the agent and the client have never heard of, registered as a
// deployment would register its own: the server sends it by name, the robot hears it among
// the others, and nothing outside protocol/ changed for it.
TEST(ServerFast, AThirdProfileIsDrivenByNameWithNoChangeOutsideTheProtocol) {
  const LinkProfile& third = test_support::third_profile();  // registered before the robot lists what it hears
  LiveSystem system;
  auto client = system.client();
  v1::DriveRequest drive = fast_drive(40, 2);
  drive.mutable_options()->set_profile(test_support::kThirdProfile);
  const auto result = read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, drive); });
  ASSERT_TRUE(result.status.ok()) << result.status.error_message();
  EXPECT_EQ(result.responses.back().progress().event(), v1::FRAME_EVENT_CONFIRMED);
  int transmitted = 0;
  for (const auto& r : result.responses) {
    EXPECT_EQ(r.progress().profile(), test_support::kThirdProfile);
    if (r.progress().event() != v1::FRAME_EVENT_TRANSMITTING) continue;
    ++transmitted;
    // Its tones are its own: none below its lowest band, 200 Hz above fast's.
    const double lowest_hz = *std::min_element(r.progress().tones_hz().begin(), r.progress().tones_hz().end());
    EXPECT_GE(lowest_hz, third.hops().band_first_bin[0][0] * 25.0);
    EXPECT_LT(fast_profile().hops().band_first_bin[0][0] * 25.0, third.hops().band_first_bin[0][0] * 25.0);
  }
  EXPECT_GE(transmitted, 1);
  const std::string expected = command::describe(command::quantised_payload(command::DriveForDuration{40, 2}));
  EXPECT_EQ(system.commands_executed(), std::vector<std::string>{expected});
}

TEST(ServerFast, ConsecutiveCommandsGetConsecutiveSequenceNumbersAndMixWithTheSeed) {
  LiveSystem system;
  auto client = system.client();
  std::optional<std::uint8_t> next;  // the number after the previous command's
  for (double speed : {10.0, 20.0, 30.0}) {
    const auto r =
        read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, fast_drive(speed, 1)); });
    ASSERT_TRUE(r.status.ok()) << r.status.error_message();
    const auto sequence = static_cast<std::uint8_t>(r.responses.back().progress().sequence());
    if (next) {
      EXPECT_EQ(sequence, *next);
    }
    next = static_cast<std::uint8_t>((sequence + 1) % 16);
  }
  // The next command without a profile goes out under the server's default, the seed's.
  v1::ResetRequest reset;
  const auto seed = read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, reset); });
  ASSERT_TRUE(seed.status.ok()) << seed.status.error_message();
  EXPECT_EQ(seed.responses.back().progress().profile(), "seed");
  EXPECT_EQ(system.words_heard(), std::vector<int>{0});
  EXPECT_EQ(system.commands_executed().size(), 3u) << "a seed RESET executes no command";
}

TEST(ServerFast, AFrameRetransmittedAfterLostAcksIsExecutedOnce) {
  LiveSystemOptions options;
  options.robot_answers = false;  // every ACK is lost: the sender retransmits
  LiveSystem system(options);
  auto client = system.client();
  v1::DriveRequest request = fast_drive(40, 2);
  request.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_FAIL);
  const auto result =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, request); });
  EXPECT_EQ(result.status.error_code(), grpc::StatusCode::ABORTED) << result.status.error_message();
  int transmissions = 0;
  for (const auto& r : result.responses) {
    const auto e = r.progress().event();
    transmissions += e == v1::FRAME_EVENT_TRANSMITTING || e == v1::FRAME_EVENT_RETRANSMITTING;
  }
  const int expected = 1 + fast_profile().timing.auto_retransmissions;
  EXPECT_EQ(transmissions, expected);
  EXPECT_EQ(system.intact_frames_heard(), expected) << "the robot heard every transmission";
  EXPECT_EQ(system.commands_executed().size(), 1u) << "and executed the command once";
}
