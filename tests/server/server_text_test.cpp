// Hostile text through the real dtmf-server process into a real PostgreSQL: every string a
// caller sends is either stored verbatim and read back intact, or refused with
// INVALID_ARGUMENT naming its field, before anything is queued or stored. Nothing may end
// in the store's `.rejected` file (a row PostgreSQL refused after the API answered OK).
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include "db/temp_database.h"
#include "dtmf/v1/teleop.grpc.pb.h"
#include "support/free_port.h"
#include "support/processes.h"

using namespace dtmf;
namespace fs = std::filesystem;

namespace {

class ServerText : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_);
    port_ = test_support::free_port();
    pid_ = test_support::start_process(std::string(DTMF_SERVER_PATH) + " --address 127.0.0.1 --port " +
                                           std::to_string(port_) + " --audio-out wav:" + path("sent.wav") +
                                           " --audio-in none --on-unconfirmed continue --db " + db_.url() +
                                           " --spill-file " + path("server.spill"),
                                       path("server.log"));
    channel_ = grpc::CreateChannel("127.0.0.1:" + std::to_string(port_), grpc::InsecureChannelCredentials());
    ASSERT_TRUE(channel_->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(10))) << log();
    stub_ = v1::TeleopService::NewStub(channel_);
  }
  void TearDown() override {
    test_support::stop_process(pid_);
    fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string log() const { return test_support::run_command("cat " + path("server.log")).out; }

  grpc::Status start_run(const std::string& label, const std::string& notes, std::string* run_id = nullptr) {
    grpc::ClientContext context;
    v1::StartRunRequest request;
    request.set_label(label);
    request.set_notes(notes);
    v1::StartRunResponse response;
    const grpc::Status status = stub_->StartRun(&context, request, &response);
    if (status.ok()) {
      grpc::ClientContext end_context;
      v1::EndRunRequest end;
      end.set_run_id(response.run_id());
      v1::EndRunResponse ended;
      EXPECT_TRUE(stub_->EndRun(&end_context, end, &ended).ok());
      if (run_id) *run_id = response.run_id();
    }
    return status;
  }

  std::vector<v1::Run> list_runs() {
    grpc::ClientContext context;
    v1::ListRunsResponse response;
    const grpc::Status status = stub_->ListRuns(&context, v1::ListRunsRequest{}, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return {response.runs().begin(), response.runs().end()};
  }

  const fs::path dir_ = fs::path(::testing::TempDir()) / ("server-text-" + std::to_string(::getpid()));
  test_support::TempDatabase db_;
  int port_ = 0, pid_ = 0;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::TeleopService::Stub> stub_;
};

void expect_refused(const grpc::Status& status, const std::string& field, const std::string& what) {
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << what << ": " << status.error_message();
  EXPECT_EQ(status.error_message().rfind(field + ":", 0), 0u) << what << " names the field: " << status.error_message();
}

}  // namespace

TEST_F(ServerText, HostileLabelsAndNotesAreStoredVerbatimOrRefusedNamingTheField) {
  // Stored verbatim: whatever is valid text, SQL and markup included.
  const std::vector<std::pair<std::string, std::string>> stored = {
      {"Robert'); DROP TABLE test_runs; --", "'; SELECT pg_sleep(10); -- \\x00 $$ $1"},
      {"\xF0\x9F\xA4\x96 robot \xF0\x9F\x94\x8A 4 m \xE2\x80\x94 \xE6\xB5\x8B\xE8\xAF\x95",
       "line one\nline two\ttabbed \xF0\x9F\x98\x80"},
      {"<script>alert(1)</script> %s %n {} \\N", "\"quoted\" \\backslash\\ ${HOME} `ls`"},
      {std::string(100, 'x'), std::string(2000, 'y')},  // exactly the limits
  };
  std::vector<std::string> run_ids;
  for (const auto& [label, notes] : stored) {
    const grpc::Status status = start_run(label, notes, &run_ids.emplace_back());
    ASSERT_TRUE(status.ok()) << label << ": " << status.error_message();
  }

  // Refused, naming the field; not one of them becomes a run.
  const std::string nul_label("general\0evil", 12);
  expect_refused(start_run(nul_label, ""), "label", "a NUL in the label");
  expect_refused(start_run("general", std::string("a\0b", 3)), "notes", "a NUL in the notes");
  expect_refused(start_run("bad \xFF\xFE utf-8", ""), "label", "invalid UTF-8");
  expect_refused(start_run("overlong \xC0\xAF slash", ""), "label", "an overlong encoding");
  expect_refused(start_run("surrogate \xED\xA0\x80", ""), "label", "an encoded surrogate");
  expect_refused(start_run("general", "bad \xC3"), "notes", "a truncated sequence");
  expect_refused(start_run(std::string(1 << 20, 'a'), ""), "label", "1 MiB");
  expect_refused(start_run("general", std::string(1 << 20, 'n')), "notes", "1 MiB of notes");
  expect_refused(start_run(std::string(101, 'x'), ""), "label", "one character over");
  expect_refused(start_run("two\nlines", ""), "label", "a line break in a label");
  expect_refused(start_run("escape \x1b[31mred", ""), "label", "a terminal escape");
  expect_refused(start_run("", ""), "label", "an empty label");

  // Read back intact through the API (which first flushes the server's store), newest
  // first, and nothing else; the notes straight from the table.
  const auto runs = list_runs();
  ASSERT_EQ(runs.size(), stored.size());
  for (std::size_t i = 0; i < stored.size(); ++i) {
    EXPECT_EQ(runs[stored.size() - 1 - i].label(), stored[i].first);
    EXPECT_EQ(db_.query<std::string>("SELECT notes FROM test_runs WHERE id = '" + run_ids[i] + "'"), stored[i].second);
  }
  EXPECT_EQ(db_.query<long>("SELECT count(*) FROM test_runs"), static_cast<long>(stored.size()));
  EXPECT_FALSE(fs::exists(path("server.spill.rejected"))) << log();
}

TEST_F(ServerText, EveryTextFieldOfEveryRequestIsChecked) {
  // A NUL in each field a caller can send, before anything is queued.
  {
    grpc::ClientContext context;
    v1::RunTestSequenceRequest request;
    request.set_label(std::string("seq\0", 4));
    v1::RunTestSequenceResponse response;
    auto reader = stub_->RunTestSequence(&context, request);
    EXPECT_FALSE(reader->Read(&response)) << "nothing streamed";
    expect_refused(reader->Finish(), "label", "RunTestSequence label");
  }
  {
    grpc::ClientContext context;
    v1::RunTestSequenceRequest request;
    request.set_label("ok");
    request.set_notes(std::string(2001, 'n'));
    v1::RunTestSequenceResponse response;
    auto reader = stub_->RunTestSequence(&context, request);
    EXPECT_FALSE(reader->Read(&response));
    expect_refused(reader->Finish(), "notes", "RunTestSequence notes");
  }
  {
    grpc::ClientContext context;
    v1::DriveRequest request;
    request.set_speed_percent(10);
    request.mutable_options()->set_profile(std::string("fast\0", 5));
    v1::DriveResponse response;
    auto reader = stub_->Drive(&context, request);
    EXPECT_FALSE(reader->Read(&response));
    expect_refused(reader->Finish(), "options.profile", "a profile with a NUL");
  }
  {
    grpc::ClientContext context;
    v1::ResetRequest request;
    request.mutable_options()->set_profile("f\xFF");
    v1::ResetResponse response;
    auto reader = stub_->Reset(&context, request);
    EXPECT_FALSE(reader->Read(&response));
    expect_refused(reader->Finish(), "profile", "a profile that is not UTF-8");
  }
  {
    grpc::ClientContext context;
    v1::DecideRequest request;
    request.set_command_id(std::string(1 << 20, 'c'));
    request.set_decision(v1::DECISION_CONTINUE);
    v1::DecideResponse response;
    expect_refused(stub_->Decide(&context, request, &response), "command_id", "a 1 MiB command id");
  }
  {
    grpc::ClientContext context;
    v1::EndRunRequest request;
    request.set_run_id(std::string("\0", 1));
    v1::EndRunResponse response;
    expect_refused(stub_->EndRun(&context, request, &response), "run_id", "EndRun");
  }
  {
    grpc::ClientContext context;
    v1::GetReportRequest request;
    request.set_run_id("\xE2\x82");
    v1::GetReportResponse response;
    expect_refused(stub_->GetReport(&context, request, &response), "run_id", "GetReport");
  }
  // Nothing was queued: no command row, no run, nothing played.
  EXPECT_EQ(db_.query<long>("SELECT count(*) FROM commands"), 0);
  EXPECT_EQ(db_.query<long>("SELECT count(*) FROM test_runs"), 0);
  EXPECT_FALSE(fs::exists(path("server.spill.rejected")));
}

// A body that is not the method's request message at all is the caller's fault too: it is
// refused as INVALID_ARGUMENT saying what to send, not INTERNAL, and nothing is stored.
TEST_F(ServerText, ABodyThatIsNotARequestMessageIsInvalidArgument) {
  grpc::GenericStub generic(channel_);
  for (const std::string& body : {std::string("\x0a\x7f garbage", 10), std::string("\xff\xff\xff\xff", 4)}) {
    grpc::ClientContext context;
    grpc::Slice slice(body);
    grpc::ByteBuffer request(&slice, 1), response;
    std::promise<grpc::Status> done;
    generic.UnaryCall(&context, "/dtmf.v1.TeleopService/StartRun", grpc::StubOptions(), &request, &response,
                      [&](grpc::Status status) { done.set_value(status); });
    const grpc::Status status = done.get_future().get();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
    EXPECT_NE(status.error_message().find("could not be parsed"), std::string::npos) << status.error_message();
  }
  EXPECT_TRUE(list_runs().empty());
}
