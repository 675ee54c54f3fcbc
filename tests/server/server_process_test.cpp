// dtmf-server as users run it: a process with health and reflection (what grpcurl and
// health probes use), writing what it plays to a file when there is no sound card, and
// shutting down gracefully on SIGTERM.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <set>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "signal/tone_listener.h"
#include "support/free_port.h"
#include "support/run_command.h"
#include "support/wait_for.h"

using namespace dtmf;
namespace fs = std::filesystem;

namespace {

using test_support::free_port;

class ServerProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_);
    port_ = free_port();
    const std::string command = std::string(DTMF_SERVER_PATH) + " --address 127.0.0.1 --port " + std::to_string(port_) +
                                " --audio-out wav:" + path("sent.wav") + " --audio-in none --db none " + extra_flags() +
                                " > /dev/null 2> " + path("server.log") + " & echo $!";
    pid_ = std::stoi(test_support::run_command(command).out);
    channel_ = grpc::CreateChannel("localhost:" + std::to_string(port_), credentials());
    ASSERT_TRUE(channel_->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(10)))
        << test_support::run_command("cat " + path("server.log")).out;
  }
  void TearDown() override {
    if (pid_ > 0) ::kill(pid_, SIGKILL);
    fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  virtual std::string extra_flags() { return ""; }
  virtual std::shared_ptr<grpc::ChannelCredentials> credentials() { return grpc::InsecureChannelCredentials(); }
  // Sends SIGTERM and waits for the process to go; its log.
  std::string terminate() {
    ::kill(pid_, SIGTERM);
    EXPECT_TRUE(test_support::wait_until([this] { return ::kill(pid_, 0) != 0; }, std::chrono::seconds(10)))
        << "still running 10 s after SIGTERM";
    pid_ = -1;
    return test_support::run_command("cat " + path("server.log")).out;
  }

  fs::path dir_ = fs::path(::testing::TempDir()) / ("server-process-" + std::to_string(::getpid()));
  int port_ = 0;
  int pid_ = -1;
  std::shared_ptr<grpc::Channel> channel_;
};

// grpc.health.v1.Health/Check answers SERVING, with no metadata.
void expect_serving(const std::shared_ptr<grpc::Channel>& channel) {
  auto health = grpc::health::v1::Health::NewStub(channel);
  grpc::ClientContext context;
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  ASSERT_TRUE(health->Check(&context, request, &response).ok());
  EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

}  // namespace

TEST_F(ServerProcess, HealthAndReflectionAnswer) {
  expect_serving(channel_);

  auto reflection = grpc::reflection::v1alpha::ServerReflection::NewStub(channel_);
  grpc::ClientContext reflection_context;
  auto stream = reflection->ServerReflectionInfo(&reflection_context);
  grpc::reflection::v1alpha::ServerReflectionRequest list;
  list.set_list_services("");
  ASSERT_TRUE(stream->Write(list));
  grpc::reflection::v1alpha::ServerReflectionResponse listed;
  ASSERT_TRUE(stream->Read(&listed));
  std::set<std::string> services;
  for (const auto& s : listed.list_services_response().service()) services.insert(s.name());
  EXPECT_TRUE(services.count("dtmf.v1.TeleopService"));
  EXPECT_TRUE(services.count("grpc.health.v1.Health"));
  // The RPCs, as grpcurl describe shows them.
  grpc::reflection::v1alpha::ServerReflectionRequest describe;
  describe.set_file_containing_symbol("dtmf.v1.TeleopService");
  ASSERT_TRUE(stream->Write(describe));
  grpc::reflection::v1alpha::ServerReflectionResponse described;
  ASSERT_TRUE(stream->Read(&described));
  ASSERT_GT(described.file_descriptor_response().file_descriptor_proto_size(), 0);
  const std::string file = described.file_descriptor_response().file_descriptor_proto(0);
  for (const char* rpc : {"Drive", "Turn", "Stop", "Reset", "RunTestSequence", "Decide", "StartRun", "GetReport"}) {
    EXPECT_NE(file.find(rpc), std::string::npos) << rpc;
  }
  // Health is described too: grpcurl and buf curl call it through reflection alone.
  grpc::reflection::v1alpha::ServerReflectionRequest describe_health;
  describe_health.set_file_containing_symbol("grpc.health.v1.Health");
  ASSERT_TRUE(stream->Write(describe_health));
  grpc::reflection::v1alpha::ServerReflectionResponse health_described;
  ASSERT_TRUE(stream->Read(&health_described));
  ASSERT_GT(health_described.file_descriptor_response().file_descriptor_proto_size(), 0)
      << health_described.error_response().error_message();
  std::string health_file;  // the file and what it imports
  for (const auto& proto : health_described.file_descriptor_response().file_descriptor_proto()) health_file += proto;
  for (const char* rpc : {"Check", "Watch", "HealthCheckResponse"}) {
    EXPECT_NE(health_file.find(rpc), std::string::npos) << rpc;
  }
  stream->WritesDone();
  stream->Finish();
}

TEST_F(ServerProcess, WithoutARobotFramesGoUnansweredAndTheFileHoldsThem) {
  auto client = v1::TeleopService::NewStub(channel_);
  grpc::ClientContext context;
  v1::ResetRequest request;
  request.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_CONTINUE);
  auto reader = client->Reset(&context, request);
  v1::ResetResponse response;
  std::vector<v1::FrameEvent> events;
  while (reader->Read(&response)) events.push_back(response.progress().event());
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_EQ(events, (std::vector<v1::FrameEvent>{v1::FRAME_EVENT_QUEUED, v1::FRAME_EVENT_TRANSMITTING,
                                                 v1::FRAME_EVENT_NO_ANSWER, v1::FRAME_EVENT_RETRANSMITTING,
                                                 v1::FRAME_EVENT_NO_ANSWER, v1::FRAME_EVENT_CONTINUED}));
  const std::string log = terminate();
  EXPECT_NE(log.find("shutting down"), std::string::npos) << log;
  auto listener = signal::chord_listener(seed_profile());
  std::vector<std::uint32_t> heard;
  for (const auto& h : listener.feed(physical::read_audio_file(path("sent.wav"), 48000))) heard.push_back(h.symbol);
  EXPECT_EQ(heard, (std::vector<std::uint32_t>{0, 0}));  // the frame and its one retransmission
}

TEST_F(ServerProcess, SigtermFinishesTheChordOnAirAndEndsQueuedCallsUnavailable) {
  std::promise<void> on_air;
  auto drive = std::async(std::launch::async, [this, &on_air] {
    auto client = v1::TeleopService::NewStub(channel_);
    grpc::ClientContext context;
    v1::DriveRequest request;
    request.set_speed_percent(10);
    auto reader = client->Drive(&context, request);
    v1::DriveResponse response;
    bool transmitting = false;
    while (reader->Read(&response)) {
      if (!transmitting && response.progress().event() == v1::FRAME_EVENT_TRANSMITTING) {
        transmitting = true;
        on_air.set_value();
      }
    }
    if (!transmitting) on_air.set_value();  // ended before: the checks below say how
    return reader->Finish();
  });
  on_air.get_future().wait();  // its first chord is on air
  const std::string log = terminate();
  const grpc::Status status = drive.get();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE) << status.error_message();
  EXPECT_NE(status.error_message().find("shutting down"), std::string::npos) << status.error_message();
  // The chord on air was played whole: the file holds one complete frame.
  auto listener = signal::chord_listener(seed_profile());
  const auto sent = physical::read_audio_file(path("sent.wav"), 48000);
  EXPECT_GE(sent.size(), static_cast<std::size_t>(seed_profile().samples_for_ms(seed_profile().timing.chord_ms)));
  std::size_t frames = 0;
  for (const auto& h : listener.feed(sent)) frames += h.symbol == 0 ? 1 : 0;
  EXPECT_EQ(frames, 1u) << log;
}

// TLS and a bearer token, as a server reachable from a network should run.
class SecuredServerProcess : public ServerProcess {
 protected:
  std::string extra_flags() override {
    const std::string cert = path("cert.pem"), key = path("key.pem");
    EXPECT_EQ(test_support::run_command("openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
                                        "-addext subjectAltName=DNS:localhost -keyout " +
                                        key + " -out " + cert)
                  .exit_code,
              0);
    std::ofstream(path("token")) << "tok-123\n";
    ::chmod(path("token").c_str(), 0600);  // a secret: the server refuses it if others may read it
    ::chmod(key.c_str(), 0600);
    return "--tls-cert " + cert + " --tls-key " + key + " --auth-token-file " + path("token");
  }
  std::shared_ptr<grpc::ChannelCredentials> credentials() override {
    grpc::SslCredentialsOptions tls;
    tls.pem_root_certs = test_support::run_command("cat " + path("cert.pem")).out;
    return grpc::SslCredentials(tls);
  }
};

TEST_F(SecuredServerProcess, ServesTlsAndDemandsTheToken) {
  auto client = v1::TeleopService::NewStub(channel_);
  v1::ResetRequest request;
  request.mutable_options()->set_on_unconfirmed(v1::UNCONFIRMED_POLICY_CONTINUE);
  {
    grpc::ClientContext context;
    auto reader = client->Reset(&context, request);
    v1::ResetResponse response;
    while (reader->Read(&response)) {
    }
    EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
  }
  grpc::ClientContext context;
  context.AddMetadata("authorization", "Bearer tok-123");
  auto reader = client->Reset(&context, request);
  v1::ResetResponse response;
  while (reader->Read(&response)) {
  }
  EXPECT_TRUE(reader->Finish().ok());
  // A plaintext client gets nowhere.
  auto plain = grpc::CreateChannel("localhost:" + std::to_string(port_), grpc::InsecureChannelCredentials());
  EXPECT_FALSE(plain->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(2)));
}

// A bearer token on a plaintext server, as on the robot's own computer: loopback only, and
// plaintext clients (grpcurl -plaintext, buf curl --http2-prior-knowledge) are served.
class TokenOnLoopbackServerProcess : public ServerProcess {
 protected:
  std::string extra_flags() override {
    std::ofstream(path("token")) << "tok-456\n";
    ::chmod(path("token").c_str(), 0600);
    return "--auth-token-file " + path("token");
  }
};

TEST_F(TokenOnLoopbackServerProcess, RefusesCallsWithoutTheTokenButAnswersHealth) {
  auto client = v1::TeleopService::NewStub(channel_);
  v1::ListRunsRequest request;
  v1::ListRunsResponse response;
  {
    grpc::ClientContext context;
    const auto status = client->ListRuns(&context, request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_NE(status.error_message().find("authorization: Bearer"), std::string::npos) << status.error_message();
  }
  {
    grpc::ClientContext context;
    context.AddMetadata("authorization", "Bearer tok-457");
    const auto status = client->ListRuns(&context, request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_NE(status.error_message().find("not this server's"), std::string::npos) << status.error_message();
  }
  {
    grpc::ClientContext context;
    context.AddMetadata("authorization", "Bearer tok-456");
    // Past the token: this server has no database, and says so.
    EXPECT_EQ(client->ListRuns(&context, request, &response).error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  }
  expect_serving(channel_);  // no token needed
}

// Issue 34: dtmfctl left a call refused for its token with exit code 3, "the robot did not
// confirm"; a script could not tell a missing token from a robot out of earshot. Now 5.
TEST_F(TokenOnLoopbackServerProcess, DtmfctlWithoutTheTokenExitsWithItsOwnCode) {
  const std::string dtmfctl = std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_);
  std::ofstream(path("wrong")) << "tok-457\n";
  std::ofstream(path("right")) << "tok-456\n";
  for (const std::string call : {"stop --on-unconfirmed fail", "drive --speed 20", "runs", "report 1"}) {
    const auto without = test_support::run_command(dtmfctl + " " + call + " < /dev/null");
    EXPECT_EQ(without.exit_code, 5) << call << ": " << without.out;
    EXPECT_NE(without.out.find("bearer token"), std::string::npos) << call << ": " << without.out;
    const auto wrong =
        test_support::run_command(dtmfctl + " --token-file " + path("wrong") + " " + call + " < /dev/null");
    EXPECT_EQ(wrong.exit_code, 5) << call << ": " << wrong.out;
    EXPECT_NE(wrong.out.find("not this server's"), std::string::npos) << call << ": " << wrong.out;
  }
  // Past the token the codes are as before: this server has no database (3), and health
  // needs no token (0).
  EXPECT_EQ(test_support::run_command(dtmfctl + " --token-file " + path("right") + " runs").exit_code, 3);
  EXPECT_EQ(test_support::run_command(dtmfctl + " health").exit_code, 0);
  const auto help = test_support::run_command(std::string(DTMFCTL_PATH) + " --help");
  EXPECT_NE(help.out.find("5 the server refused the caller"), std::string::npos) << help.out;
}

namespace {

// dtmf-server --robots: two robots by name, neither in the room.
class RobotsFileServerProcess : public ServerProcess {
 protected:
  std::string extra_flags() override {
    std::ofstream(path("robots.json")) << R"([{"name": "alpha", "address": 1},
                                              {"name": "beta", "address": 2, "model": "waffle"}])";
    ::chmod(path("robots.json").c_str(), 0644);  // whatever the umask: no one else may change it
    return "--robots " + path("robots.json");
  }
  test_support::CommandResult dtmfctl(const std::string& args) {
    return test_support::run_command(std::string(DTMFCTL_PATH) + " --server 127.0.0.1:" + std::to_string(port_) + " " +
                                     args + " 2>&1");
  }
};

}  // namespace

TEST_F(RobotsFileServerProcess, DtmfctlListsTheRobotsAndACommandMustNameOneItKnows) {
  const auto listed = dtmfctl("robots");
  ASSERT_EQ(listed.exit_code, 0) << listed.out;
  EXPECT_NE(listed.out.find("alpha"), std::string::npos) << listed.out;
  EXPECT_NE(listed.out.find("address 2"), std::string::npos) << listed.out;
  EXPECT_NE(listed.out.find("waffle"), std::string::npos) << listed.out;
  const auto json = dtmfctl("robots --json");
  ASSERT_EQ(json.exit_code, 0) << json.out;
  EXPECT_NE(json.out.find(R"({"address":1,"key_id":"","last_answered_unix_ms":0,"model":"burger","name":"alpha"})"),
            std::string::npos)
      << json.out;

  for (const std::string robot : {"--robot gamma ", ""}) {
    const auto refused = dtmfctl(robot + "reset --on-unconfirmed continue");
    EXPECT_EQ(refused.exit_code, 2) << refused.out;
    EXPECT_NE(refused.out.find("options.robot"), std::string::npos) << refused.out;
    EXPECT_NE(refused.out.find("alpha, beta"), std::string::npos) << refused.out;
  }
  // Named: it goes on air (no robot answers here, so it continues unconfirmed).
  const auto sent = dtmfctl("--robot beta reset --on-unconfirmed continue --json");
  EXPECT_EQ(sent.exit_code, 0) << sent.out;
  EXPECT_NE(sent.out.find(R"("robot":"beta")"), std::string::npos) << sent.out;
}

// Issue 59: options.robot had no bound, and a name no robot has was echoed whole into the
// status: 3 MB, newlines included. It is checked as the label is, before any robot is looked
// up: one line, at most 64 characters; the refusal names the field and the bound, and shows
// none of the text.
TEST_F(RobotsFileServerProcess, AHugeOrMultilineRobotNameIsRefusedWithABoundedOneLineDetail) {
  auto client = v1::TeleopService::NewStub(channel_);
  std::string huge;
  while (huge.size() < 3'000'000) huge += "gamma\n[info] a forged log line\n";
  const auto reset = [&](const std::string& robot) {
    grpc::ClientContext context;
    v1::ResetRequest request;
    request.mutable_options()->set_robot(robot);
    auto reader = client->Reset(&context, request);
    v1::ResetResponse response;
    while (reader->Read(&response)) {
    }
    return reader->Finish();
  };
  const auto teleop = [&](const std::string& robot) {
    grpc::ClientContext context;
    auto stream = client->Teleop(&context);
    v1::TeleopRequest first;
    first.set_linear_mps(0.05);
    first.set_lease_s(1);
    first.mutable_options()->set_robot(robot);
    stream->Write(first);
    stream->WritesDone();
    v1::TeleopResponse response;
    while (stream->Read(&response)) {
    }
    return stream->Finish();
  };
  const std::pair<std::string, std::string> cases[] = {
      {huge, "options.robot: holds the control character U+000A (one line only)"},
      {std::string(65, 'g'), "options.robot: 65 characters, at most 64 allowed"},
      {"gam\x1b[2Jma", "options.robot: holds the control character U+001B"},
      // Right-to-left override: no control character, but no robot's name either; shown escaped.
      {std::string("\xe2\x80\xae") + "ammag", R"(options.robot: "\xe2\x80\xaeammag" is no robot's name)"},
  };
  const auto printable = [](const std::string& text) {
    return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  };
  for (const auto& [robot, expected] : cases) {
    for (const grpc::Status& status : {reset(robot), teleop(robot)}) {
      const std::string& said = status.error_message();
      EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << said.substr(0, 200);
      EXPECT_EQ(said.rfind(expected, 0), 0u) << said.substr(0, 200);
      EXPECT_LT(said.size(), 200u);
      EXPECT_TRUE(printable(said)) << said.substr(0, 200);
    }
  }
  // A profile name is shown the same way.
  grpc::ClientContext context;
  v1::ResetRequest request;
  request.mutable_options()->set_profile(std::string("\xe2\x80\xae") + "fast");
  auto reader = client->Reset(&context, request);
  v1::ResetResponse response;
  while (reader->Read(&response)) {
  }
  const grpc::Status profile = reader->Finish();
  EXPECT_EQ(profile.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(profile.error_message().rfind(R"(options.profile: "\xe2\x80\xaefast" is no profile)", 0), 0u)
      << profile.error_message();
  EXPECT_TRUE(printable(profile.error_message())) << profile.error_message();
}

TEST(ServerFlags, UsageErrorsAndABusyPortAreClear) {
  EXPECT_EQ(test_support::run_command(std::string(DTMF_SERVER_PATH) + " --port 70000").exit_code, 2);
  EXPECT_EQ(test_support::run_command(std::string(DTMF_SERVER_PATH) + " --on-unconfirmed maybe").exit_code, 2);
  const auto help = test_support::run_command(std::string(DTMF_SERVER_PATH) + " --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* flag : {"--address", "--port", "--audio-out", "--audio-in", "--tls-cert", "--auth-token-file",
                           "--on-unconfirmed", "--max-queue", "Exit codes"}) {
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  }
  const auto tls = test_support::run_command(
      std::string(DTMF_SERVER_PATH) +
      " --audio-out wav:/dev/null --audio-in none --db none --tls-cert /nonexistent.pem --tls-key /nonexistent.key");
  EXPECT_EQ(tls.exit_code, 1);
  EXPECT_NE(tls.out.find("/nonexistent"), std::string::npos) << tls.out;
  // A token in clear text off loopback is refused before anything is opened, with the ways out.
  const std::string token = ::testing::TempDir() + "/server-flags-token";
  std::ofstream(token) << "t\n";
  ::chmod(token.c_str(), 0600);
  const auto exposed = test_support::run_command(std::string(DTMF_SERVER_PATH) +
                                                 " --audio-out wav:/dev/null --audio-in none --db none --address "
                                                 "0.0.0.0 --port 0 --auth-token-file " +
                                                 token);
  EXPECT_EQ(exposed.exit_code, 2) << exposed.out;
  for (const char* hint : {"clear text", "--tls-cert", "--address 127.0.0.1"}) {
    EXPECT_NE(exposed.out.find(hint), std::string::npos) << hint << " in " << exposed.out;
  }
  const auto half_tls = test_support::run_command(
      std::string(DTMF_SERVER_PATH) + " --audio-out wav:/dev/null --audio-in none --db none --tls-cert " + token);
  EXPECT_EQ(half_tls.exit_code, 2) << half_tls.out;
  EXPECT_NE(half_tls.out.find("--tls-key"), std::string::npos) << half_tls.out;
}

namespace {

// dtmf-server with `flags` and no sound card, stopped after 20 s if it has not stopped by
// itself (a server that accepts what it should refuse would serve on: exit code 124).
test_support::CommandResult start_server(const std::string& flags) {
  return test_support::run_command("timeout 20 " + std::string(DTMF_SERVER_PATH) +
                                   " --audio-out wav:/dev/null --audio-in none --db none --port " +
                                   std::to_string(free_port()) + " " + flags);
}

std::string write_file(const fs::path& file, const std::string& text, mode_t mode) {
  fs::remove(file);
  std::ofstream(file) << text;
  ::chmod(file.c_str(), mode);
  return file.string();
}

}  // namespace

// Issue 34: an empty token file read as "no token" and turned authentication off; a token
// file or TLS key others could read was taken. Each now stops the server at start, saying
// what to do, without a byte of the file.
TEST(ServerFlags, AnEmptyTokenFileOrASecretOthersMayReadStopsTheServerAtStart) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("server-secrets-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const std::string blank : {"", "\n", "  \n \n"}) {
    const std::string token = write_file(dir / "empty-token", blank, 0600);
    const auto r = start_server("--auth-token-file " + token);
    EXPECT_EQ(r.exit_code, 1) << r.out;
    for (const std::string& hint :
         {token, std::string("empty"), "openssl rand -hex 32 > " + token, std::string("chmod 600")}) {
      EXPECT_NE(r.out.find(hint), std::string::npos) << hint << " in " << r.out;
    }
  }
  const std::string token = write_file(dir / "token", "Zq8rT0kenV4lue\n", 0644);
  const auto readable = start_server("--auth-token-file " + token);
  EXPECT_EQ(readable.exit_code, 1) << readable.out;
  EXPECT_NE(readable.out.find("mode 0644"), std::string::npos) << readable.out;
  EXPECT_NE(readable.out.find("chmod 600 " + token), std::string::npos) << readable.out;
  EXPECT_EQ(readable.out.find("Zq8rT0kenV4lue"), std::string::npos) << readable.out;
  ::chmod(token.c_str(), 0600);

  const std::string cert = (dir / "cert.pem").string(), key = (dir / "key.pem").string();
  ASSERT_EQ(test_support::run_command("openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
                                      "-addext subjectAltName=DNS:localhost -keyout " +
                                      key + " -out " + cert)
                .exit_code,
            0);
  ::chmod(cert.c_str(), 0644);  // public
  for (const mode_t mode : {0640u, 0604u}) {
    ::chmod(key.c_str(), mode);
    const auto r = start_server("--tls-cert " + cert + " --tls-key " + key + " --auth-token-file " + token);
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_NE(r.out.find("chmod 600 " + key), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("PRIVATE KEY"), std::string::npos) << r.out;
  }
  fs::remove_all(dir);
}

// Issue 34: any --address that began with "127." counted as loopback, so a name such as
// 127.0.0.1.nip.io (which resolves wherever its owner likes) was served without TLS or a
// token. It gets protected mode's refusal now, before anything is opened.
TEST(ServerFlags, ANameThatMerelyBeginsWith127IsNotLoopback) {
  const auto r = start_server("--address 127.0.0.1.nip.io");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--allow-anyone-on-the-network"), std::string::npos) << r.out;
}

TEST(ServerFlags, ABadRobotsFileStopsTheServerNamingWhatIsWrong) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("server-robots-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string file = write_file(dir / "robots.json", R"([{"name": "alpha", "address": 9}])", 0644);
  const auto bad = start_server("--robots " + file);
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_NE(bad.out.find("robot 1 \"alpha\": address 9 is outside 0..7"), std::string::npos) << bad.out;
  // The one robot's flags and a robots file exclude each other.
  const std::string good = write_file(dir / "good.json", R"([{"name": "alpha", "address": 1}])", 0644);
  const auto both = start_server("--robots " + good + " --robot-address 3");
  EXPECT_EQ(both.exit_code, 2) << both.out;
  EXPECT_NE(both.out.find("--robot-address"), std::string::npos) << both.out;
  fs::remove_all(dir);
}

// Issue 59: the robots file decides which key each robot gets, and was trusted as found: one
// that others may write (0666) was taken silently, and whoever wrote it could drop a robot's
// key, so that robot was sent frames it refuses, Stop included. It is now checked as the
// files that hold secrets are, and more: no group or others may write it, it must be this
// user's or root's, and not a symbolic link. Each refusal says what is wrong and the fix.
TEST(ServerFlags, ARobotsFileOthersMayChangeStopsTheServerWithTheFix) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("server-robots-trust-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string json = R"([{"name": "alpha", "address": 1}])";
  for (const mode_t mode : {0666u, 0620u, 0602u}) {
    const std::string file = write_file(dir / "robots.json", json, mode);
    const auto r = start_server("--robots " + file);
    EXPECT_EQ(r.exit_code, 1) << r.out;
    char shown[8];
    std::snprintf(shown, sizeof shown, "%04o", static_cast<unsigned>(mode));
    EXPECT_NE(r.out.find(std::string("mode ") + shown), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("chmod go-w " + file), std::string::npos) << r.out;
  }
  const std::string file = write_file(dir / "robots.json", json, 0644);
  const fs::path link = dir / "link.json";
  fs::create_symlink(file, link);
  const auto linked = start_server("--robots " + link.string());
  EXPECT_EQ(linked.exit_code, 1) << linked.out;
  EXPECT_NE(linked.out.find("symbolic link"), std::string::npos) << linked.out;
  EXPECT_NE(linked.out.find("--robots " + file), std::string::npos) << linked.out;
  if (::geteuid() == 0) {  // only root can give a file away
    ASSERT_EQ(::chown(file.c_str(), 4242, 4242), 0);
    const auto theirs = start_server("--robots " + file);
    EXPECT_EQ(theirs.exit_code, 1) << theirs.out;
    EXPECT_NE(theirs.out.find("belongs to user 4242"), std::string::npos) << theirs.out;
    EXPECT_NE(theirs.out.find("chown 0 " + file), std::string::npos) << theirs.out;
  }
  fs::remove_all(dir);
}

// Issue 59: a key file named for two robots, or a robot's key that is the room key, was
// refused for the wrong reason: the second counter store found the first one's lock ("another
// process keeps its sender counter ..."). The keys are compared when read, before any counter
// store is opened, and the refusal names both entries and why a key is one robot's alone.
TEST(ServerFlags, AKeySharedByTwoRobotsOrWithTheRoomIsRefusedForWhatItIs) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("server-robots-keys-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto key = [&](const std::string& name) {
    const std::string file = (dir / name).string();
    EXPECT_EQ(test_support::run_command(std::string(DTMFCTL_PATH) + " keygen " + file).exit_code, 0);
    return file;
  };
  const std::string a = key("a.key"), b = key("b.key");
  const std::string a_copy = (dir / "a-copy.key").string();
  ASSERT_EQ(test_support::run_command("cp -p " + a + " " + a_copy).exit_code, 0);
  const auto robots = [&](const std::string& name, const std::string& key_a, const std::string& key_b) {
    return write_file(dir / name,
                      R"([{"name": "alpha", "address": 1, "key": ")" + key_a +
                          R"("}, {"name": "beta", "address": 2, "key": ")" + key_b + R"("}])",
                      0644);
  };
  struct Case {
    std::string flags;
    std::vector<std::string> said;
  };
  const Case cases[] = {
      {"--robots " + robots("one-file.json", a, a), {R"(robots "alpha" and "beta")", "one key"}},
      {"--robots " + robots("one-key.json", a, a_copy), {R"(robots "alpha" and "beta")", "one key"}},
      {"--robots " + robots("room.json", a, b) + " --room-key " + b, {R"(robot "beta")", "the room key"}},
      {"--key " + a + " --room-key " + a_copy, {R"(robot "robot")", "the room key"}},
  };
  for (const Case& c : cases) {
    const auto r = start_server(c.flags + " --state-dir " + (dir / "state").string());
    EXPECT_EQ(r.exit_code, 2) << c.flags << ": " << r.out;
    for (const std::string& said : c.said) EXPECT_NE(r.out.find(said), std::string::npos) << said << " in " << r.out;
    EXPECT_EQ(r.out.find("another process"), std::string::npos) << r.out;
  }
  fs::remove_all(dir);
}
