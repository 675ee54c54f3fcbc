// The seed's test sequence through the gRPC API, the simulated room and the robot agent,
// logged to a real PostgreSQL: 65 frames, and the run's seed-style report read back.
#include <gtest/gtest.h>

#include "db/temp_database.h"
#include "live_system.h"

using namespace dtmf;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;

TEST(ServerWithDatabase, RunTestSequenceSendsSixtyFiveFramesAndReportsTheRun) {
  test_support::TempDatabase db;
  LiveSystemOptions options;
  options.database = db.url();
  options.default_policy = server::Policy::Continue;
  LiveSystem system(options);
  auto client = system.client();

  v1::RunTestSequenceRequest request;
  request.set_label("general");
  request.set_notes("simulated room, 1 m");
  const auto result = read_stream<v1::RunTestSequenceResponse>(
      [&](grpc::ClientContext& c) { return client->RunTestSequence(&c, request); });
  ASSERT_TRUE(result.status.ok()) << result.status.error_message();
  ASSERT_FALSE(result.responses.empty());
  const auto& last = result.responses.back();
  EXPECT_EQ(last.frames_total(), 65u);
  EXPECT_EQ(last.frames_done(), 65u);
  EXPECT_EQ(last.command_count(), 27u);
  EXPECT_EQ(last.progress().event(), v1::FRAME_EVENT_CONFIRMED);
  EXPECT_EQ(system.words_heard().size(), 65u);
  const std::string run_id = last.run_id();

  grpc::ClientContext runs_context;
  v1::ListRunsResponse runs;
  ASSERT_TRUE(client->ListRuns(&runs_context, v1::ListRunsRequest{}, &runs).ok());
  ASSERT_EQ(runs.runs_size(), 1);
  EXPECT_EQ(runs.runs(0).label(), "general");
  EXPECT_EQ(runs.runs(0).transmissions_sent(), 65);
  EXPECT_GT(runs.runs(0).ended_unix_ms(), runs.runs(0).started_unix_ms());

  grpc::ClientContext report_context;
  v1::GetReportRequest report_request;  // the latest run
  v1::GetReportResponse report;
  ASSERT_TRUE(client->GetReport(&report_context, report_request, &report).ok());
  EXPECT_EQ(report.run().run_id(), run_id);
  EXPECT_EQ(report.transmissions_sent(), 65);
  EXPECT_EQ(report.sender_confirmed(), 65);
  EXPECT_DOUBLE_EQ(report.sender_confirmed_rate_pct(), 100.0);
  EXPECT_GE(report.frame_attempts(), 65);
  EXPECT_FALSE(report.has_error_catch_rate_pct());  // nothing faulty to catch: N/A
  EXPECT_GT(report.response_time_avg_ms(), 0);
  EXPECT_LT(report.response_time_max_ms(), 1500);
  std::printf("sequence: %lld attempts, response %.0f / %.0f / %.0f ms (avg / min / max)\n",
              static_cast<long long>(report.frame_attempts()), report.response_time_avg_ms(),
              report.response_time_min_ms(), report.response_time_max_ms());
  // The robot side logs nothing here (the in-process agent has no database), so the
  // receptions are the agent tests' business; the sender's rows are all in.
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM commands WHERE outcome = 'confirmed' AND run_id = '" + run_id + "'"),
            27);

  grpc::ClientContext missing_context;
  v1::GetReportRequest missing;
  missing.set_run_number(999);
  EXPECT_EQ(client->GetReport(&missing_context, missing, &report).error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST(ServerWithDatabase, StartAndEndRunFrameManualCommands) {
  test_support::TempDatabase db;
  LiveSystemOptions options;
  options.database = db.url();
  LiveSystem system(options);
  auto client = system.client();
  grpc::ClientContext start_context;
  v1::StartRunRequest start;
  start.set_label("manual");
  v1::StartRunResponse started;
  ASSERT_TRUE(client->StartRun(&start_context, start, &started).ok());
  grpc::ClientContext again_context;
  EXPECT_EQ(client->StartRun(&again_context, start, &started).error_code(), grpc::StatusCode::FAILED_PRECONDITION);

  v1::StopRequest stop;
  ASSERT_TRUE(
      read_stream<v1::StopResponse>([&](grpc::ClientContext& c) { return client->Stop(&c, stop); }).status.ok());
  grpc::ClientContext end_context;
  v1::EndRunRequest end;
  end.set_run_id(started.run_id());
  v1::EndRunResponse ended;
  ASSERT_TRUE(client->EndRun(&end_context, end, &ended).ok());

  grpc::ClientContext report_context;
  v1::GetReportRequest report_request;
  report_request.set_run_id(started.run_id());
  report_request.set_include_frames(true);
  v1::GetReportResponse report;
  ASSERT_TRUE(client->GetReport(&report_context, report_request, &report).ok());
  EXPECT_EQ(report.run().label(), "manual");
  EXPECT_EQ(report.transmissions_sent(), 2);
  EXPECT_EQ(report.sender_confirmed(), 2);
  // Each chord, in order: the Stop command's mode word and its parameter, both answered.
  ASSERT_EQ(report.frames_size(), 2);
  for (int i = 0; i < 2; ++i) {
    const auto& frame = report.frames(i);
    EXPECT_EQ(frame.command(), "stop");
    EXPECT_EQ(frame.position(), static_cast<unsigned>(i));
    EXPECT_EQ(frame.attempt(), 1u);
    EXPECT_EQ(frame.frame_bits().size(), 16u);
    EXPECT_EQ(frame.tones_hz_size(), 4);
    EXPECT_EQ(frame.answer(), "ack");
    ASSERT_TRUE(frame.has_response_time_ms());
    EXPECT_GT(frame.response_time_ms(), 0);
    EXPECT_LT(frame.response_time_ms(), 1500);
    EXPECT_FALSE(frame.has_latency_ms());  // the in-process robot logs nothing here
    EXPECT_GE(frame.chord_started_unix_ms(), report.run().started_unix_ms());
  }
  EXPECT_LT(report.frames(0).chord_started_unix_ms(), report.frames(1).chord_started_unix_ms());
}
