// dtmf-server: the sender. A gRPC service whose commands become chords on the loudspeaker,
// answered by the robot's ACK / NACK chords on the microphone.
//
//   dtmf-server                              # default speaker and microphone, port 50051
//   dtmf-server --audio-out wav:sent.wav --audio-in none --db none   # no sound card
//   dtmf-server --robots robots.json         # several robots, each by name (server/robot_roster.h)
// Exit codes: 0 stopped cleanly, 1 an audio device, the database or the port could not be had,
// 2 bad usage.
//
// Here: the order the server starts and stops in. Its flags are server_flags.cpp, the parts
// they make (security, robots, profile, audio, gRPC) server_setup.cpp.
#include <unistd.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <csignal>
#include <thread>

#include "server_flags.h"
#include "server_setup.h"
#include "store_recorder.h"
#include "teleop_service.h"

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

int run(const dtmf::server::ServerFlags& f) {
  using namespace dtmf;
  const server::ServerSecurity security = server::read_security(f);
  const std::shared_ptr<grpc::ServerCredentials> credentials = server::server_credentials(security, f.address);
  if (server::open_to_anyone(security, f.address)) {
    spdlog::warn(
        "serving {} without TLS and a bearer token (--allow-anyone-on-the-network): anyone who can reach "
        "port {} can drive the robot",
        f.address, f.port);
  }
  // The keys before any device: a key file others may read stops the server here.
  std::vector<server::RobotLinks> robots = server::robot_links(f);
  std::vector<std::unique_ptr<link::Link>> room_links = link::make_links(program::room_link_options(f.keys));
  const LinkProfile& profile = server::default_profile(f, robots);
  const bool any_keyed =
      std::any_of(robots.begin(), robots.end(), [](const auto& r) { return r.links.front()->keyed(); });
  if (!any_keyed) {
    spdlog::info("no key: frames go unauthenticated (dtmf-server --key FILE)");
  } else if (f.allow_unauthenticated) {
    spdlog::warn(
        "--allow-unauthenticated-commands: commands may go out without a MAC (profile seed); a keyed robot refuses "
        "them unless it runs with --accept-unauthenticated, and their ACKs, which anyone within earshot can play, are "
        "reported as unauthenticated. Stop always goes authenticated");
  }
  const store::DatabaseUrl db = store::parse_database_flag(f.db);
  if (!store::database_disabled(db)) {
    auto connection = store::connect(db);
    spdlog::info("database {}: schema version {}", store::describe_database(db),
                 store::migrate(*connection).version_after);
  }
  auto [speaker, microphone] = server::open_audio(f, profile);

  store::StoreOptions store_options;
  store_options.database = db;
  store_options.spill_path = f.spill_file.empty() ? store::default_spill_path("dtmf-server") : f.spill_file;
  store::Store store(store_options);
  char machine[256] = {};
  ::gethostname(machine, sizeof machine - 1);
  const std::string hostname = f.host.empty() ? std::string(machine) : f.host;
  server::StoreRecorder recorder(store, hostname);
  server::Transmitter transmitter(
      std::move(robots), profile, std::move(speaker), std::move(microphone), recorder,
      {.max_queue = f.max_queue, .realtime_audio = true, .allow_unauthenticated = f.allow_unauthenticated},
      std::move(room_links));

  server::ServiceOptions options;
  options.database = db;
  options.defaults.policy = f.on_unconfirmed == "ask"        ? server::Policy::Ask
                            : f.on_unconfirmed == "continue" ? server::Policy::Continue
                                                             : server::Policy::Fail;
  options.defaults.decision_timeout = std::chrono::milliseconds(static_cast<long>(f.decision_timeout_s * 1000));
  options.host = hostname;
  server::TeleopService service(transmitter, store, options);

  int port = 0;
  const std::unique_ptr<grpc::Server> grpc_server = server::start_serving(f, credentials, service, port);
  spdlog::info("serving dtmf.v1.TeleopService on {}:{} ({}{}), default profile {}", f.address, port,
               f.tls_cert.empty() ? "plaintext" : "TLS", security.auth_token.empty() ? "" : ", bearer token",
               profile.name);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));

  spdlog::info("shutting down: finishing the chord on air");
  grpc_server->GetHealthCheckService()->SetServingStatus(false);
  transmitter.shutdown();
  grpc_server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(5));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("dtmf-server"));
  dtmf::server::ServerFlags f;
  CLI::App app{"dtmf-server: the gRPC control API that drives a TurtleBot3 by sound"};
  dtmf::server::add_server_flags(app, f);
  return dtmf::program::audio_program_main(app, argc, argv, f.program, [&] { return run(f); });
}
