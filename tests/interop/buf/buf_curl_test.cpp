// The gRPC API through a third-party, reflection-driven client: `buf curl` (npm's
// @bufbuild/buf, installed into the build tree by scripts/test), as grpcurl and Postman
// users reach it. It knows nothing of our proto files: every service, method and message
// comes from the server's reflection. Against a live system of real processes: dtmf-agent
// and dtmf-server through the PulseAudio air, logging to PostgreSQL (ctest fixtures).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "support/free_port.h"
#include "support/processes.h"
#include "support/run_command.h"

using dtmf::test_support::run_command;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(::testing::TempDir()) / ("buf-curl-" + std::to_string(::getpid()));

// buf curl prints each response message as one (indented) JSON object.
std::vector<nlohmann::json> json_values(const std::string& text) {
  std::vector<nlohmann::json> values;
  std::istringstream in(text);
  while ((in >> std::ws).peek() != std::char_traits<char>::eof()) {
    nlohmann::json value;
    in >> value;
    values.push_back(value);
  }
  return values;
}

class BufCurl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fs::create_directories(kDir);
    const std::string db = std::getenv("DTMF_DB_URL") ? std::getenv("DTMF_DB_URL") : "none";
    agent_ = dtmf::test_support::start_process(std::string(DTMF_AGENT_PATH) +
                                                   " --audio default --ack-out default --cmd-vel sim --db " + db +
                                                   " --spill-file " + (kDir / "agent.spill").string(),
                                               (kDir / "agent.log").string());
    port_ = dtmf::test_support::free_port();
    server_ = dtmf::test_support::start_process(std::string(DTMF_SERVER_PATH) + " --address 127.0.0.1 --port " +
                                                    std::to_string(port_) + " --db " + db + " --spill-file " +
                                                    (kDir / "server.spill").string(),
                                                (kDir / "server.log").string());
    ASSERT_TRUE(dtmf::test_support::wait_healthy(DTMFCTL_PATH, port_));
    // Ready once the robot confirms a Stop through the air (outside any run: no report counts it).
    ASSERT_TRUE(dtmf::test_support::wait_robot_answers(DTMFCTL_PATH, port_)) << "the robot never confirmed a Stop";
  }
  static void TearDownTestSuite() {
    for (int pid : {agent_, server_}) dtmf::test_support::stop_process(pid);
    fs::remove_all(kDir);
  }

  // `buf curl` with gRPC over plaintext HTTP/2, as the README shows it.
  static dtmf::test_support::CommandResult buf_curl(const std::string& args, bool with_stderr = false) {
    return run_command(std::string(DTMF_BUF_PATH) + " curl --protocol grpc --http2-prior-knowledge " + args,
                       with_stderr);
  }
  static std::string url(const std::string& method = "") {
    return "http://127.0.0.1:" + std::to_string(port_) + (method.empty() ? "" : "/" + method);
  }

  static inline int agent_ = 0, server_ = 0, port_ = 0;
};

}  // namespace

TEST_F(BufCurl, ListsEveryServiceAndMethodThroughReflection) {
  auto r = buf_curl("--list-services " + url());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* service :
       {"dtmf.v1.TeleopService", "grpc.health.v1.Health", "grpc.reflection.v1alpha.ServerReflection"}) {
    EXPECT_NE(r.out.find(service), std::string::npos) << service << "\n" << r.out;
  }
  r = buf_curl("--list-methods " + url());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* method : {"dtmf.v1.TeleopService/Drive", "dtmf.v1.TeleopService/GetReport",
                             "grpc.health.v1.Health/Check", "grpc.health.v1.Health/Watch"}) {
    EXPECT_NE(r.out.find(method), std::string::npos) << method << "\n" << r.out;
  }
}

TEST_F(BufCurl, HealthCheckAnswersServing) {
  const auto r = buf_curl(url("grpc.health.v1.Health/Check"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto values = json_values(r.out);
  ASSERT_EQ(values.size(), 1u) << r.out;
  EXPECT_EQ(values[0]["status"], "SERVING");
}

TEST_F(BufCurl, AFastDriveStreamsToConfirmedAndItsRunHasAReport) {
  auto r = buf_curl("-d '{\"label\": \"buf curl\"}' " + url("dtmf.v1.TeleopService/StartRun"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string run_id = json_values(r.out).at(0)["runId"];

  r = buf_curl("-d '{\"speed_percent\": 40, \"duration_s\": 1, \"options\": {\"profile\": \"fast\"}}' " +
               url("dtmf.v1.TeleopService/Drive"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::vector<std::string> events;
  for (const auto& response : json_values(r.out)) {
    // .value(): operator[] on a const json with a missing key is undefined (it crashed).
    const auto progress = response.value("progress", nlohmann::json::object());
    events.push_back(progress.value("event", ""));
    EXPECT_EQ(progress.value("profile", ""), "fast") << response;
    // A queued command has no frames yet: they are numbered as they go on air.
    EXPECT_EQ(progress.value("frameBits", "").size(), events.back() == "FRAME_EVENT_QUEUED" ? 0u : 50u) << response;
  }
  ASSERT_FALSE(events.empty()) << r.out;
  EXPECT_EQ(events.front(), "FRAME_EVENT_QUEUED");
  EXPECT_EQ(events.back(), "FRAME_EVENT_CONFIRMED") << r.out;
  EXPECT_NE(std::find(events.begin(), events.end(), "FRAME_EVENT_ACK"), events.end()) << r.out;

  r = buf_curl("-d '{\"run_id\": \"" + run_id + "\"}' " + url("dtmf.v1.TeleopService/EndRun"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  r = buf_curl("-d '{\"run_id\": \"" + run_id + "\", \"include_frames\": true}' " +
               url("dtmf.v1.TeleopService/GetReport"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto report = json_values(r.out).at(0);
  EXPECT_EQ(report["run"]["runId"], run_id);
  EXPECT_EQ(report["run"]["label"], "buf curl");
  EXPECT_EQ(report["run"]["profile"], "seed");  // the server's default; the command asked for fast
  // int64 fields are JSON strings in protobuf's JSON mapping.
  EXPECT_EQ(report["transmissionsSent"], "1");
  EXPECT_EQ(report["senderConfirmed"], "1");
  ASSERT_TRUE(report.contains("frames")) << report;
  ASSERT_EQ(report.at("frames").size(), 1u) << report;
  EXPECT_EQ(report.at("frames").at(0).value("answer", ""), "ack");
}

TEST_F(BufCurl, ABadValueIsInvalidArgumentNamingTheField) {
  const auto r = buf_curl("-d '{\"speed_percent\": 120}' " + url("dtmf.v1.TeleopService/Drive"), true);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("invalid_argument"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed_percent"), std::string::npos) << r.out;
}
