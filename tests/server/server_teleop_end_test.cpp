// How a Teleop stream ends, through the whole system (real gRPC on loopback, the
// transmitter, a simulated room, the robot agent): whatever ends it, the server lives and the
// robot is free for the next stream by the time the client hears the end.
#include <gtest/gtest.h>

#include <atomic>

#include "live_system.h"
#include "teleop_client.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::TeleopClient;

// Whatever the transmitter throws mid-stream (here an exception no one foresaw, from its
// observer on the third frame's Queued event), the stream ends with a status that names it,
// the server lives, and the slot is free for the next stream.
TEST(ServerTeleop, AnExceptionFromTheTransmitterEndsTheStreamNotTheServer) {
  std::atomic<int> queued{0};
  std::atomic<bool> armed{true};
  LiveSystemOptions options;
  options.before_recording = [&](const server::ProgressEvent& event) {
    // From the third on: a joint renewal's, on the loudspeaker's thread, or a frame's of the stream.
    if (event.kind == server::ProgressEvent::Kind::Queued && armed && ++queued >= 3)
      throw std::runtime_error("the disk caught fire");
  };
  LiveSystem system(options);
  auto stub = system.client();
  {
    TeleopClient teleop(*stub, 0.05, 0, 0.5);
    ASSERT_TRUE(teleop.confirmed(0.05, 0, 3s));
    teleop.target(0.06, 0);  // another frame, and renewals: the third submit throws
    const auto failed = teleop.event(v1::FRAME_EVENT_FAILED, 3s);
    ASSERT_TRUE(failed) << "the stream did not report the failure";
    EXPECT_NE(failed->progress().detail().find("the disk caught fire"), std::string::npos);
    ASSERT_TRUE(teleop.ended(3s)) << "the server did not end the stream";
    const grpc::Status ended = teleop.finish();
    EXPECT_EQ(ended.error_code(), grpc::StatusCode::INTERNAL) << ended.error_message();
    EXPECT_NE(ended.error_message().find("the disk caught fire"), std::string::npos) << ended.error_message();
    EXPECT_GE(queued.load(), 3);
  }
  armed = false;
  // The server lives, and the slot is free.
  TeleopClient next(*stub, 0.02, 0, 0.5);
  EXPECT_TRUE(next.confirmed(0.02, 0, 3s)) << "the slot was not freed";
  EXPECT_TRUE(next.close().ok());
}

// A client that opens its next stream the moment the last one's status reaches it finds the
// robot free: the server frees it before the status goes, not when gRPC is done with the call
// (which comes later, and once refused the next stream as "another Teleop stream drives").
TEST(ServerTeleop, TheRobotIsFreeWhenTheClientHearsTheStreamEnded) {
  LiveSystem system;
  auto stub = system.client();
  for (int stream = 0; stream < 40; ++stream) {
    TeleopClient teleop(*stub, 0.02, 0, 0.5);
    const grpc::Status ended = teleop.close();
    ASSERT_TRUE(ended.ok()) << "stream " << stream << ": " << ended.error_message();
  }
  TeleopClient last(*stub, 0.03, 0, 0.5);
  EXPECT_TRUE(last.confirmed(0.03, 0, 3s));
  EXPECT_TRUE(last.close().ok());
}
