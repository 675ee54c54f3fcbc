// Teleop through the whole system: a real gRPC bidirectional stream on loopback, the
// transmitter, a simulated room, the robot agent and its cmd_vel. The client behaves as
// dtmfctl teleop does: it sends its target when it changes and repeats it every 100 ms.
#include <gtest/gtest.h>

#include "live_system.h"
#include "security/link_key.h"
#include "support/wait_for.h"
#include "teleop_client.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;
using test_support::TeleopClient;
using test_support::wait_until;

namespace {

using Clock = std::chrono::steady_clock;

// When the robot's cmd_vel was last non-zero, and whether it is zero at the end.
struct StopSeen {
  std::optional<Clock::time_point> last_moving;
  bool still_at_end = false;
};
StopSeen stop_seen(LiveSystem& system) {
  StopSeen seen;
  for (const auto& s : system.velocities()) {
    if (s.velocity.linear_mps != 0 || s.velocity.angular_radps != 0) seen.last_moving = s.at;
  }
  const auto all = system.velocities();
  seen.still_at_end = !all.empty() && all.back().velocity == agent::Velocity{};
  return seen;
}

// The lease as a frame carries it: rounded down to a step of 0.125 s from 0.25 s.
double carried_lease_s(double lease_s) { return 0.25 + std::floor((lease_s - 0.25) / 0.125 + 1e-9) * 0.125; }

// Until the robot's cmd_vel is (linear, angular), within the payload's steps, for at most 2 s
// (the ramp, 2.5 m/s² and 25 rad/s², takes a fraction of that).
bool reaches(LiveSystem& system, double linear, double angular) {
  return wait_until(
      [&] {
        const agent::Velocity v = system.last_velocity();
        return std::abs(v.linear_mps - linear) < 0.0002 && std::abs(v.angular_radps - angular) < 0.012;
      },
      2s);
}

// Until the robot stands (its newest cmd_vel zero), for at most the lease and 2 s more.
bool stands_within(LiveSystem& system, double lease_s) {
  return wait_until([&] { return system.last_velocity() == agent::Velocity{}; },
                    std::chrono::milliseconds(static_cast<int>(lease_s * 1000)) + 2s);
}

}  // namespace

TEST(ServerTeleop, DrivesAnArcThenReversesWithStatusAndEveryFrameStored) {
  LiveSystem system;
  auto stub = system.client();
  TeleopClient teleop(*stub, 0.1, 0.5, 1.0);
  const auto arc = teleop.confirmed(0.1, 0.5, 3s);
  ASSERT_TRUE(arc) << "no confirmed arc";
  EXPECT_GT(arc->response_time_ms(), 0);
  EXPECT_LT(arc->response_time_ms(), 500);
  EXPECT_DOUBLE_EQ(arc->target_linear_mps(), 0.1);
  EXPECT_NEAR(arc->lease_s(), carried_lease_s(1.0), 1e-9);
  EXPECT_EQ(arc->progress().profile(), "fast");
  EXPECT_TRUE(reaches(system, 0.1, 0.5)) << "cmd_vel " << system.last_velocity().linear_mps << " m/s "
                                         << system.last_velocity().angular_radps << " rad/s";

  teleop.target(-0.05, 0);
  ASSERT_TRUE(teleop.confirmed(-0.05, 0, 3s)) << "no confirmed reverse";
  EXPECT_TRUE(reaches(system, -0.05, 0)) << "cmd_vel " << system.last_velocity().linear_mps << " m/s";
  // Kept: held for longer than one lease, which only renewals can do.
  std::this_thread::sleep_for(1500ms);
  EXPECT_NEAR(system.last_velocity().linear_mps, -0.05, 0.0002) << "the lease was renewed";
  const auto status = teleop.responses().back();
  EXPECT_GT(status.link_quality(), 0.9) << "a quiet room at 1 m";
  // The stream's own frames: the reverse; the lease since renewed by joint renewals
  // (Transmitter::keep_renewed), unanswered, so not in the window.
  EXPECT_GE(status.frames_in_window(), 1u);
  EXPECT_GT(status.lease_left_s(), 0);
  const auto closed_at = Clock::now();
  const grpc::Status closed = teleop.close();
  EXPECT_TRUE(closed.ok()) << closed.error_message();
  ASSERT_TRUE(stands_within(system, carried_lease_s(1.0))) << "the robot never stopped";
  const StopSeen seen = stop_seen(system);
  ASSERT_TRUE(seen.last_moving);
  EXPECT_TRUE(seen.still_at_end);
  EXPECT_LE(std::chrono::duration<double>(*seen.last_moving - closed_at).count(), carried_lease_s(1.0) + 0.2)
      << "the lease lapsed when the stream ended";
  // Every frame was a velocity command, executed as such.
  int velocities = 0;
  for (const auto& c : system.commands_executed()) velocities += c.rfind("velocity ", 0) == 0;
  EXPECT_GE(velocities, 4) << "the arc, the reverse and renewals";
}

TEST(ServerTeleop, OneStreamDrivesAtATimeAndStopOvertakesAndEndsIt) {
  LiveSystem system;
  auto stub = system.client();
  TeleopClient first(*stub, 0.05, 0, 0.5);
  ASSERT_TRUE(first.confirmed(0.05, 0, 3s));

  TeleopClient second(*stub, 0.1, 0, 0.5);
  const grpc::Status refused = second.finish();
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(refused.error_message().find("another Teleop stream drives the robot"), std::string::npos)
      << refused.error_message();
  v1::DriveRequest drive;
  drive.set_speed_percent(50);
  drive.mutable_options()->set_profile("fast");
  const auto drove = read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return stub->Drive(&c, drive); });
  EXPECT_EQ(drove.status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(drove.status.error_message().find("Drive refused: a Teleop stream drives the robot"), std::string::npos);

  v1::StopRequest stop;
  stop.mutable_options()->set_profile("fast");
  const auto stopped = read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return stub->Stop(&c, stop); });
  EXPECT_TRUE(stopped.status.ok()) << stopped.status.error_message();
  EXPECT_EQ(system.last_velocity(), agent::Velocity{}) << "Stop takes effect at once";
  const grpc::Status ended = first.finish();
  EXPECT_EQ(ended.error_code(), grpc::StatusCode::ABORTED);
  EXPECT_NE(ended.error_message().find("a Stop call overtook this Teleop stream"), std::string::npos)
      << ended.error_message();
  std::this_thread::sleep_for(1s);  // kept: a second in which nothing may drive after the Stop
  EXPECT_EQ(system.last_velocity(), agent::Velocity{}) << "nothing drove after the Stop";

  // The slot is free again.
  TeleopClient third(*stub, 0.02, 0, 0.5);
  EXPECT_TRUE(third.confirmed(0.02, 0, 3s));
  EXPECT_TRUE(third.close().ok());
}

TEST(ServerTeleop, BadTargetsAndTheSeedProfileAreInvalidArguments) {
  LiveSystem system;
  auto stub = system.client();
  {
    TeleopClient seed(*stub, 0.1, 0, 1.0, "seed");
    const grpc::Status s = seed.finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("profile seed: a velocity command needs a profile with whole-command frames"),
              std::string::npos)
        << s.error_message();
  }
  {
    TeleopClient fast(*stub, 0.5, 0, 1.0);
    const grpc::Status s = fast.finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("linear_mps 0.5 is out of range for a burger"), std::string::npos)
        << s.error_message();
  }
  {
    TeleopClient lease(*stub, 0.1, 0, 5.0);
    const grpc::Status s = lease.finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("lease_s"), std::string::npos) << s.error_message();
  }
  {
    // A bad target mid-stream ends the stream naming it; the robot stops with the lease.
    TeleopClient later(*stub, 0.1, 0, 0.5);
    ASSERT_TRUE(later.confirmed(0.1, 0, 3s));
    later.target(0.1, 9);
    const grpc::Status s = later.finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("angular_radps 9 is out of range"), std::string::npos) << s.error_message();
  }
  EXPECT_TRUE(system.words_heard().empty()) << "nothing went out under the seed profile";
}

// A joystick sends a target on every move, faster than frames go on air: the server keeps
// the newest, and the robot ends at the last one. The client's writes from its caller's
// thread meet its own 100 ms repeats here, a dozen times a second (one Write at a time on a
// gRPC stream; two at once aborted dtmf-bench-teleop).
TEST(ServerTeleop, AFloodOfTargetsDrivesTheNewestAndTheStreamEndsCleanly) {
  LiveSystem system;
  auto stub = system.client();
  TeleopClient teleop(*stub, 0, 0, 1.0);
  int sent = 0;
  for (const auto end = Clock::now() + 1500ms; Clock::now() < end; ++sent) teleop.target(0.001 * (sent % 100), 0);
  ASSERT_GT(sent, 1000) << "the flood must outnumber the frames by far";
  teleop.target(0.08, -0.3);
  ASSERT_TRUE(teleop.confirmed(0.08, -0.3, 3s)) << "the newest target was never confirmed";
  EXPECT_TRUE(reaches(system, 0.08, -0.3))
      << "cmd_vel " << system.last_velocity().linear_mps << " m/s " << system.last_velocity().angular_radps << " rad/s";
  EXPECT_TRUE(teleop.close().ok());
  // Frames went out one at a time, each for the newest target then: a few per 100 ms, not one per message.
  EXPECT_LT(teleop.responses().size(), static_cast<std::size_t>(sent) / 10);
}

TEST(ServerTeleop, ACancelledStreamStopsTheRobotWithinTheLease) {
  LiveSystem system;
  auto stub = system.client();
  TeleopClient teleop(*stub, 0.15, -1.0, 0.5);
  ASSERT_TRUE(teleop.confirmed(0.15, -1.0, 3s));
  const auto velocity_frames = [&] {
    int n = 0;
    for (const auto& c : system.commands_executed()) n += c.rfind("velocity ", 0) == 0;
    return n;
  };
  ASSERT_TRUE(wait_until([&] { return velocity_frames() >= 2; }, 3s)) << "no renewal executed";
  const auto cancelled_at = Clock::now();
  teleop.cancel();
  EXPECT_EQ(teleop.finish().error_code(), grpc::StatusCode::CANCELLED);
  ASSERT_TRUE(stands_within(system, carried_lease_s(0.5))) << "the robot never stopped";
  const StopSeen seen = stop_seen(system);
  ASSERT_TRUE(seen.last_moving);
  EXPECT_TRUE(seen.still_at_end);
  EXPECT_LE(std::chrono::duration<double>(*seen.last_moving - cancelled_at).count(), carried_lease_s(0.5) + 0.2);
}

TEST(ServerTeleop, WithAKeyEveryVelocityFrameIsAuthenticatedAndAWrongKeyDrivesNothing) {
  const auto key = security::LinkKey::generate();
  {
    LiveSystemOptions options;
    options.sender_key = key;
    options.robot_key = key;
    LiveSystem system(options);
    auto stub = system.client();
    TeleopClient teleop(*stub, -0.1, 1.0, 0.6);
    const auto confirmed = teleop.confirmed(-0.1, 1.0, 4s);
    ASSERT_TRUE(confirmed) << "no confirmed velocity with keys on both sides";
    EXPECT_TRUE(teleop.close().ok());
    int transmitted = 0;
    for (const auto& r : teleop.responses()) {
      if (r.progress().event() != v1::FRAME_EVENT_TRANSMITTING) continue;
      ++transmitted;
      EXPECT_TRUE(r.progress().authenticated());
      if (!r.progress().synchronisation()) {
        EXPECT_EQ(r.progress().frame_bits().size(), 80u);
      }
    }
    EXPECT_GE(transmitted, 1);
    EXPECT_EQ(system.refused_frames_heard(), 0);
  }
  {
    LiveSystemOptions options;
    options.sender_key = key;
    options.robot_key = security::LinkKey::generate();
    LiveSystem system(options);
    auto stub = system.client();
    TeleopClient teleop(*stub, 0.1, 0, 0.6);
    EXPECT_FALSE(teleop.confirmed(0.1, 0, 1500ms)) << "the robot confirmed a frame of another key";
    teleop.close();
    EXPECT_GE(system.refused_frames_heard(), 1);
    for (const auto& s : system.velocities()) EXPECT_EQ(s.velocity, agent::Velocity{});
  }
}
