// The gRPC service over real gRPC on loopback, its audio through a simulated room to the
// robot agent's code, which answers with ACK / NACK: every command RPC end to end.
#include <gtest/gtest.h>

#include "support/wait_for.h"

using namespace std::chrono_literals;
using dtmf::test_support::wait_until;

#include <cmath>
#include <future>
#include <limits>
#include <set>

#include <grpcpp/generic/generic_stub.h>

#include "command/word_codec.h"
#include "live_system.h"

using namespace dtmf;
using test_support::BackgroundStream;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;

namespace {

std::vector<v1::FrameEvent> events_of(const std::vector<v1::DriveResponse>& responses) {
  std::vector<v1::FrameEvent> events;
  for (const auto& r : responses) events.push_back(r.progress().event());
  return events;
}

}  // namespace

TEST(Server, DriveStreamsEveryFrameAndEndsConfirmedWithTheRobotMoving) {
  LiveSystem system;
  auto client = system.client();
  v1::DriveRequest request;
  request.set_speed_percent(50);
  request.set_duration_s(3);
  const auto result =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, request); });
  ASSERT_TRUE(result.status.ok()) << result.status.error_message();
  const auto events = events_of(result.responses);
  EXPECT_EQ(events.front(), v1::FRAME_EVENT_QUEUED);
  EXPECT_EQ(events.back(), v1::FRAME_EVENT_CONFIRMED);
  int transmitted = 0, acked = 0;
  for (const auto& r : result.responses) {
    const v1::Progress& p = r.progress();
    EXPECT_EQ(p.frame_count(), 3u);
    EXPECT_EQ(p.command(), "drive_for_duration speed=50.0% duration=2.97s");
    if (p.event() == v1::FRAME_EVENT_TRANSMITTING) {
      EXPECT_EQ(p.frame_index(), static_cast<std::uint32_t>(transmitted));
      EXPECT_EQ(p.frame_bits().size(), 16u);
      EXPECT_EQ(p.tones_hz_size(), 4);
      ++transmitted;
    }
    if (p.event() == v1::FRAME_EVENT_ACK) {
      ++acked;
      EXPECT_GT(p.response_time_ms(), 0);
      EXPECT_LT(p.response_time_ms(), 1500);
    }
  }
  EXPECT_EQ(transmitted, 3);
  EXPECT_EQ(acked, 3);
  EXPECT_EQ(system.words_heard(), (std::vector<int>{0, 2, *command::parameter_word(command::DriveForDuration{50, 3})}));
  // cmd_vel is published on the agent's next tick (50 ms), which may follow its ACK.
  EXPECT_TRUE(wait_until([&] { return system.last_velocity().linear_mps == 0.11; }, 1s))
      << system.last_velocity().linear_mps;
}

TEST(Server, BadRequestsAreInvalidArgumentNamingTheFieldAndNeverReachTheAir) {
  LiveSystem system;
  auto client = system.client();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* name;
    std::function<grpc::Status()> call;
    const char* field;
  };
  const auto drive = [&](double speed, std::optional<double> duration, std::optional<int> policy = {}) {
    v1::DriveRequest r;
    r.set_speed_percent(speed);
    if (duration) r.set_duration_s(*duration);
    if (policy) r.mutable_options()->set_on_unconfirmed(static_cast<v1::UnconfirmedPolicy>(*policy));
    return read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, r); }).status;
  };
  const auto turn = [&](double rotation, std::optional<double> duration) {
    v1::TurnRequest r;
    r.set_rotation_percent(rotation);
    if (duration) r.set_duration_s(*duration);
    return read_stream<v1::TurnResponse>([&](grpc::ClientContext& c) { return client->Turn(&c, r); }).status;
  };
  const std::vector<Case> cases = {
      {"speed above 100", [&] { return drive(101, 1.0); }, "speed_percent"},
      {"speed negative", [&] { return drive(-5, {}); }, "speed_percent"},
      {"speed NaN", [&] { return drive(nan, {}); }, "speed_percent"},
      {"duration negative", [&] { return drive(50, -1.0); }, "duration_s"},
      {"duration above 8", [&] { return drive(50, 8.5); }, "duration_s"},
      {"duration NaN", [&] { return turn(10, nan); }, "duration_s"},
      {"rotation below -100", [&] { return turn(-100.5, {}); }, "rotation_percent"},
      {"rotation infinite", [&] { return turn(std::numeric_limits<double>::infinity(), 1.0); }, "rotation_percent"},
      {"policy unspecified", [&] { return drive(50, 1.0, 0); }, "options.on_unconfirmed"},
      {"policy unknown", [&] { return drive(50, 1.0, 42); }, "options.on_unconfirmed"},
      {"decision unspecified",
       [&] {
         v1::DecideRequest r;
         r.set_command_id("x");
         grpc::ClientContext c;
         v1::DecideResponse out;
         return client->Decide(&c, r, &out);
       },
       "decision"},
      {"decision without command",
       [&] {
         v1::DecideRequest r;
         r.set_decision(v1::DECISION_CONTINUE);
         grpc::ClientContext c;
         v1::DecideResponse out;
         return client->Decide(&c, r, &out);
       },
       "command_id"},
      {"unknown profile",
       [&] {
         v1::DriveRequest r;
         r.set_speed_percent(10);
         r.mutable_options()->set_profile("slow");
         return read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, r); }).status;
       },
       "options.profile"},
      {"sequence without label",
       [&] {
         v1::RunTestSequenceRequest r;
         return read_stream<v1::RunTestSequenceResponse>(
                    [&](grpc::ClientContext& c) { return client->RunTestSequence(&c, r); })
             .status;
       },
       "label"},
  };
  for (const Case& c : cases) {
    const grpc::Status status = c.call();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.name << ": " << status.error_message();
    EXPECT_EQ(status.error_message().rfind(c.field, 0), 0u) << c.name << ": " << status.error_message();
  }
  // Kept: what must not happen needs time to show; a frame sent would have been heard by now.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_TRUE(system.words_heard().empty());
}

TEST(Server, TenConcurrentClientsEachGetTheirCommandWholeAndOnce) {
  LiveSystem system;
  std::vector<std::future<grpc::Status>> calls;
  for (int i = 0; i < 10; ++i) {
    calls.push_back(std::async(std::launch::async, [&system, i] {
      auto client = system.client();
      v1::TurnRequest r;  // each client its own rotation, so its frames can be told apart
      r.set_rotation_percent(-90 + 20 * i);
      return read_stream<v1::TurnResponse>([&](grpc::ClientContext& c) { return client->Turn(&c, r); }).status;
    }));
  }
  for (auto& call : calls) EXPECT_TRUE(call.get().ok());
  const auto words = system.words_heard();
  ASSERT_EQ(words.size(), 30u);
  std::set<int> parameters;
  for (std::size_t k = 0; k < 30; k += 3) {
    EXPECT_EQ(words[k], 0) << k;  // RESET, mode, parameter: never interleaved
    EXPECT_EQ(words[k + 1], static_cast<int>(command::Mode::Turn)) << k;
    parameters.insert(words[k + 2]);
  }
  EXPECT_EQ(parameters.size(), 10u);  // every client's command, once
}

TEST(Server, StopOvertakesQueuedCommands) {
  LiveSystem system;
  auto client = system.client();
  v1::DriveRequest drive;
  drive.set_speed_percent(20);
  BackgroundStream<v1::DriveResponse> first([&](grpc::ClientContext& c) { return client->Drive(&c, drive); });
  ASSERT_TRUE(first.wait_for(v1::FRAME_EVENT_TRANSMITTING));  // the drive is on air
  v1::TurnRequest turn;
  turn.set_rotation_percent(30);
  BackgroundStream<v1::TurnResponse> queued([&](grpc::ClientContext& c) { return client->Turn(&c, turn); });
  ASSERT_TRUE(queued.wait_for(v1::FRAME_EVENT_QUEUED));  // the turn waits behind it
  v1::StopRequest stop;
  const auto stopped = read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return client->Stop(&c, stop); });
  EXPECT_TRUE(stopped.status.ok());
  // The drive on air ends when its chord does, and the turn queued for the same robot never
  // plays: behind the stop it would set the robot moving again (issue 59).
  for (const auto& overtaken : {first.finish().status, queued.finish().status}) {
    EXPECT_EQ(overtaken.error_code(), grpc::StatusCode::CANCELLED);
    EXPECT_NE(overtaken.error_message().find("overtaken by a Stop"), std::string::npos) << overtaken.error_message();
  }
  const auto words = system.words_heard();
  ASSERT_GE(words.size(), 3u);
  EXPECT_LE(words.size(), 4u) << "the drive's words on air when the stop came, then the stop's";
  EXPECT_EQ(words[words.size() - 2], 0);  // the stop's RESET
  EXPECT_EQ(words.back(), static_cast<int>(command::Mode::Stop));
  for (const int w : words) EXPECT_NE(w, static_cast<int>(command::Mode::Turn)) << "the queued turn played";
}

TEST(Server, ACancelledCallsQueuedFramesNeverPlay) {
  LiveSystem system;
  auto client = system.client();
  v1::DriveRequest drive;
  drive.set_speed_percent(40);
  drive.set_duration_s(1);
  BackgroundStream<v1::DriveResponse> first([&](grpc::ClientContext& c) { return client->Drive(&c, drive); });
  ASSERT_TRUE(first.wait_for(v1::FRAME_EVENT_TRANSMITTING));
  {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(800));
    v1::TurnRequest r;
    r.set_rotation_percent(-77);
    auto reader = client->Turn(&context, r);
    v1::TurnResponse response;
    bool queued = false;
    while (reader->Read(&response)) queued = queued || response.progress().event() == v1::FRAME_EVENT_QUEUED;
    EXPECT_TRUE(queued);  // it waited behind the drive, then its caller gave up
    EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  }
  EXPECT_TRUE(first.finish().status.ok());
  std::this_thread::sleep_for(std::chrono::seconds(2));  // time for a frame that should not come
  EXPECT_EQ(system.words_heard().size(), 3u);            // the drive only; no frame of the turn
}

TEST(Server, ALostAckGetsExactlyOneAutomaticRetransmissionThenThePolicy) {
  LiveSystemOptions options;
  options.robot_answers = false;
  LiveSystem system(options);
  auto client = system.client();
  v1::ResetRequest fail;
  fail.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_FAIL);
  const auto failed = read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, fail); });
  EXPECT_EQ(failed.status.error_code(), grpc::StatusCode::ABORTED) << failed.status.error_message();
  std::vector<v1::FrameEvent> events;
  for (const auto& r : failed.responses) events.push_back(r.progress().event());
  EXPECT_EQ(events, (std::vector<v1::FrameEvent>{v1::FRAME_EVENT_QUEUED, v1::FRAME_EVENT_TRANSMITTING,
                                                 v1::FRAME_EVENT_NO_ANSWER, v1::FRAME_EVENT_RETRANSMITTING,
                                                 v1::FRAME_EVENT_NO_ANSWER, v1::FRAME_EVENT_FAILED}));
  EXPECT_EQ(system.words_heard(), (std::vector<int>{0, 0}));  // the robot heard both transmissions

  // ASK: the caller is asked, retransmits once more, then continues.
  v1::ResetRequest ask;
  ask.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_ASK);
  grpc::ClientContext context;
  auto reader = client->Reset(&context, ask);
  v1::ResetResponse response;
  int asked = 0, transmissions = 0;
  while (reader->Read(&response)) {
    const auto& p = response.progress();
    if (p.event() == v1::FRAME_EVENT_TRANSMITTING || p.event() == v1::FRAME_EVENT_RETRANSMITTING) ++transmissions;
    if (p.event() != v1::FRAME_EVENT_AWAITING_DECISION) continue;
    v1::DecideRequest decide;
    decide.set_command_id(p.command_id());
    decide.set_decision(++asked == 1 ? v1::DECISION_RETRANSMIT : v1::DECISION_CONTINUE);
    grpc::ClientContext c;
    v1::DecideResponse out;
    EXPECT_TRUE(client->Decide(&c, decide, &out).ok());
  }
  EXPECT_TRUE(reader->Finish().ok());
  EXPECT_EQ(asked, 2);
  EXPECT_EQ(transmissions, 3);
  EXPECT_EQ(response.progress().event(), v1::FRAME_EVENT_CONTINUED);
}

TEST(Server, AFullQueueAnswersResourceExhausted) {
  LiveSystemOptions options;
  options.max_queue = 1;
  LiveSystem system(options);
  auto client = system.client();
  const auto reset = [&](grpc::ClientContext& c) { return client->Reset(&c, v1::ResetRequest{}); };
  BackgroundStream<v1::ResetResponse> on_air(reset);
  ASSERT_TRUE(on_air.wait_for(v1::FRAME_EVENT_TRANSMITTING));
  BackgroundStream<v1::ResetResponse> waiting(reset);
  ASSERT_TRUE(waiting.wait_for(v1::FRAME_EVENT_QUEUED));  // the queue's one place is taken
  const auto refused = read_stream<v1::ResetResponse>(reset);
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << refused.status.error_message();
  EXPECT_TRUE(on_air.finish().status.ok());
  EXPECT_TRUE(waiting.finish().status.ok());
}

TEST(Server, ABearerTokenIsRequiredWhenConfigured) {
  LiveSystemOptions options;
  options.auth_token = "s3cret";
  LiveSystem system(options);
  auto client = system.client();
  v1::ResetRequest r;
  const auto denied = read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, r); });
  EXPECT_EQ(denied.status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_NE(denied.status.error_message().find("Bearer"), std::string::npos);
  const auto wrong =
      read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, r); }, "guess");
  EXPECT_EQ(wrong.status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(system.intact_frames_heard(), 0);  // refused calls send nothing
  // The check runs in the transport, before the request is even parsed: a request that
  // cannot be parsed is refused for its missing token, not for its text.
  v1::StartRunRequest unparsable;
  unparsable.set_label("run");
  std::string bytes = unparsable.SerializeAsString();
  bytes.back() = '\xff';  // the label is no longer UTF-8
  grpc::GenericStub generic(system.channel());
  for (const std::string token : {"", "s3cret"}) {
    grpc::ClientContext context;
    if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
    grpc::Slice slice(bytes);
    grpc::ByteBuffer request(&slice, 1), response;
    std::promise<grpc::Status> done;
    generic.UnaryCall(&context, "/dtmf.v1.TeleopService/StartRun", grpc::StubOptions(), &request, &response,
                      [&](grpc::Status status) { done.set_value(status); });
    const grpc::Status status = done.get_future().get();
    if (token.empty()) {
      EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED) << status.error_message();
    } else {
      EXPECT_NE(status.error_code(), grpc::StatusCode::UNAUTHENTICATED) << status.error_message();
      EXPECT_NE(status.error_code(), grpc::StatusCode::OK);
    }
  }
  const auto allowed =
      read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, r); }, "s3cret");
  EXPECT_TRUE(allowed.status.ok()) << allowed.status.error_message();
}

TEST(Server, ReportsWithoutADatabaseSaySo) {
  LiveSystem system;
  auto client = system.client();
  grpc::ClientContext context;
  v1::GetReportRequest request;
  v1::GetReportResponse response;
  const auto status = client->GetReport(&context, request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(status.error_message().find("--db"), std::string::npos);
}

TEST(Server, AnAudioDeviceThatGoesAwayMakesCommandsUnavailable) {
  LiveSystem system;
  auto client = system.client();
  system.pull_the_plug();
  v1::ResetRequest r;
  const auto first = read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, r); });
  EXPECT_EQ(first.status.error_code(), grpc::StatusCode::UNAVAILABLE) << first.status.error_message();
  EXPECT_NE(first.status.error_message().find("loudspeaker failed"), std::string::npos) << first.status.error_message();
  const auto next = read_stream<v1::ResetResponse>([&](grpc::ClientContext& c) { return client->Reset(&c, r); });
  EXPECT_EQ(next.status.error_code(), grpc::StatusCode::UNAVAILABLE);
}
