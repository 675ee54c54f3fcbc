// A sender with a key (docs/security.md): nothing goes on air without a MAC unless the
// operator allowed it, a Stop always goes authenticated, and an untagged ACK — a fixed chord
// anyone within earshot can play — never makes a keyed confirmation. Real gRPC on loopback,
// the transmitter, a simulated room with the keyed robot agent in it, and a stranger's
// loudspeaker beside the sender's microphone playing the seed profile's ACK again and again.
#include <gtest/gtest.h>

#include "support/wait_for.h"

#include <atomic>
#include <thread>

#include "link/link.h"
#include "live_system.h"

using namespace dtmf;
using namespace std::chrono_literals;
using dtmf::test_support::wait_until;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;

namespace {

// The seed profile's ACK, as its robot plays it: the same two tones for every frame.
std::vector<float> seed_ack() {
  const auto seed = link::make_link(seed_profile());
  link::Reception accepted;
  accepted.intact = true;
  accepted.event = link::ReceptionEvent::Command;
  auto audio = seed->answer_audio(accepted);
  audio.resize(audio.size() + static_cast<std::size_t>(seed_profile().samples_for_ms(20)), 0.0f);
  return audio;
}

// The forger: the seed's ACK on its loudspeaker without a pause, until the test ends.
class SeedAckForger {
 public:
  explicit SeedAckForger(LiveSystem& system)
      : thread_([this, &system] {
          const auto ack = seed_ack();
          while (!stop_) system.forger_speaker().write(ack);
        }) {}
  ~SeedAckForger() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

LiveSystemOptions keyed_system() {
  LiveSystemOptions options;
  options.sender_key = options.robot_key = security::LinkKey::generate();
  options.forger = true;
  return options;
}

v1::StopRequest stop_with_profile(const std::string& profile) {
  v1::StopRequest r;
  r.mutable_options()->set_profile(profile);
  return r;
}

v1::DriveRequest drive_forward(double speed, const std::string& profile = "") {
  v1::DriveRequest r;
  r.set_speed_percent(speed);
  r.mutable_options()->set_profile(profile);
  return r;
}

template <class Response>
int count(const std::vector<Response>& responses, v1::FrameEvent event) {
  int n = 0;
  for (const auto& r : responses) n += r.progress().event() == event ? 1 : 0;
  return n;
}

}  // namespace

TEST(KeyedSender, AProfileLessStopGoesAuthenticatedAndStopsTheKeyedRobotWhileASeedAckIsPlayed) {
  LiveSystem system(keyed_system());
  auto client = system.client();
  const auto drive =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, drive_forward(50)); });
  ASSERT_TRUE(drive.status.ok()) << drive.status.error_message();
  EXPECT_EQ(drive.responses.back().progress().profile(), "fast") << "with a key the default carries a MAC";
  // cmd_vel is published on the agent's next tick (50 ms), which may follow its ACK.
  ASSERT_TRUE(wait_until([&] { return system.last_velocity().linear_mps > 0; }, 1s)) << "the keyed robot drives";

  SeedAckForger forger(system);
  for (const std::string profile : {"", "seed"}) {
    const auto stop = read_stream<v1::StopResponse>(
        [&](grpc::ClientContext& c) { return client->Stop(&c, stop_with_profile(profile)); });
    ASSERT_TRUE(stop.status.ok()) << "'" << profile << "': " << stop.status.error_message();
    for (const auto& r : stop.responses) {
      if (r.progress().event() == v1::FRAME_EVENT_QUEUED) continue;
      EXPECT_EQ(r.progress().profile(), "fast") << "Stop named '" << profile << "'";
      EXPECT_TRUE(r.progress().authenticated());
    }
    const v1::Progress& last = stop.responses.back().progress();
    EXPECT_EQ(last.event(), v1::FRAME_EVENT_CONFIRMED);
    EXPECT_TRUE(last.answer_authenticated()) << "confirmed by the robot's tag, not the forger's chord";
    EXPECT_EQ(last.detail(), "");
  }
  EXPECT_TRUE(wait_until([&] { return system.last_velocity() == agent::Velocity{}; }, 1s)) << "the keyed robot stopped";
  EXPECT_EQ(system.refused_frames_heard(), 0) << "no frame without a MAC reached the robot";
}

TEST(KeyedSender, ASeedAckPlayedToItsMicrophoneConfirmsNoStop) {
  LiveSystemOptions options = keyed_system();
  options.robot_answers = false;  // only the forger answers
  LiveSystem system(options);
  SeedAckForger forger(system);
  auto client = system.client();
  for (const std::string profile : {"", "seed"}) {
    const auto stop = read_stream<v1::StopResponse>(
        [&](grpc::ClientContext& c) { return client->Stop(&c, stop_with_profile(profile)); });
    EXPECT_EQ(stop.status.error_code(), grpc::StatusCode::ABORTED) << "'" << profile << "': not confirmed";
    EXPECT_EQ(count(stop.responses, v1::FRAME_EVENT_ACK), 0);
    EXPECT_EQ(count(stop.responses, v1::FRAME_EVENT_CONFIRMED), 0);
    EXPECT_GE(count(stop.responses, v1::FRAME_EVENT_NO_ANSWER), 1);
  }
  // The robot heard the frames, authenticated (its answers are what is lost): each Stop's
  // counter synchronisation, never confirmed, so the Stop's own frame never followed.
  EXPECT_GE(system.intact_frames_heard(), 2);
  EXPECT_EQ(system.refused_frames_heard(), 0);
}

TEST(KeyedSender, ACommandNamingAProfileWithoutAMacIsRefusedNamingTheFlag) {
  LiveSystem system(keyed_system());
  auto client = system.client();
  const auto drive = read_stream<v1::DriveResponse>(
      [&](grpc::ClientContext& c) { return client->Drive(&c, drive_forward(50, "seed")); });
  EXPECT_EQ(drive.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(drive.status.error_message().find("--allow-unauthenticated-commands"), std::string::npos)
      << drive.status.error_message();
  EXPECT_NE(drive.status.error_message().find("options.profile"), std::string::npos);
  EXPECT_TRUE(drive.responses.empty());
  std::this_thread::sleep_for(300ms);  // a frame, had one been sent, would have been heard by now
  EXPECT_EQ(system.intact_frames_heard(), 0) << "nothing went on air";
}

TEST(KeyedSender, AllowedUnauthenticatedCommandsAreReportedAsSuchAndStopStillGoesAuthenticated) {
  LiveSystemOptions options = keyed_system();
  options.forger = false;
  options.allow_unauthenticated = true;
  options.robot_accepts_unauthenticated = true;
  LiveSystem system(options);
  auto client = system.client();
  const auto drive = read_stream<v1::DriveResponse>(
      [&](grpc::ClientContext& c) { return client->Drive(&c, drive_forward(50, "seed")); });
  ASSERT_TRUE(drive.status.ok()) << drive.status.error_message();
  ASSERT_GE(count(drive.responses, v1::FRAME_EVENT_ACK), 1);
  for (const auto& r : drive.responses) {
    if (r.progress().event() == v1::FRAME_EVENT_ACK) {
      EXPECT_FALSE(r.progress().answer_authenticated());
    }
  }
  const v1::Progress& confirmed = drive.responses.back().progress();
  EXPECT_EQ(confirmed.event(), v1::FRAME_EVENT_CONFIRMED);
  EXPECT_EQ(confirmed.profile(), "seed");
  EXPECT_FALSE(confirmed.answer_authenticated());
  EXPECT_NE(confirmed.detail().find("unauthenticated"), std::string::npos) << confirmed.detail();

  const auto stop = read_stream<v1::StopResponse>(
      [&](grpc::ClientContext& c) { return client->Stop(&c, stop_with_profile("seed")); });
  ASSERT_TRUE(stop.status.ok()) << stop.status.error_message();
  EXPECT_EQ(stop.responses.back().progress().profile(), "fast");
  EXPECT_TRUE(stop.responses.back().progress().answer_authenticated());
  EXPECT_TRUE(wait_until([&] { return system.last_velocity() == agent::Velocity{}; }, 1s));
}
