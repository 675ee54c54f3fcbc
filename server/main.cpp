// dtmf-server: the sender. A gRPC service whose commands become chords on the loudspeaker,
// answered by the robot's ACK / NACK chords on the microphone.
//
//   dtmf-server                              # default speaker and microphone, port 50051
//   dtmf-server --audio-out wav:sent.wav --audio-in none --db none   # no sound card
//   dtmf-server --robots robots.json         # several robots, each by name (server/robot_roster.h)
// Exit codes: 0 stopped cleanly, 1 an audio device, the database or the port could not be had,
// 2 bad usage.
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <unistd.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <thread>

#include "audio_program.h"
#include "bearer_token_auth.h"
#include "grpc/health/v1/health.pb.h"
#include "key_flags.h"
#include "physical/audio_spec.h"
#include "physical/portaudio_device.h"
#include "physical/realtime_priority.h"
#include "physical/wav_file.h"
#include "robot_roster.h"
#include "secret_file.h"
#include "shown_text.h"
#include "store_recorder.h"
#include "teleop_service.h"
#include "utf8_refusal.h"

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

// --audio-in none: a microphone that hears silence, in real time.
class Silence : public dtmf::physical::AudioSource {
 public:
  explicit Silence(int rate) : rate_(rate) {}
  std::size_t read(std::span<float> out) override {
    std::fill(out.begin(), out.end(), 0.0f);
    next_ += std::chrono::microseconds(static_cast<long long>(1e6 * static_cast<double>(out.size()) / rate_));
    std::this_thread::sleep_until(next_);
    return out.size();
  }
  int sample_rate_hz() const override { return rate_; }
  std::string describe() const override { return "none (silence)"; }

 private:
  int rate_;
  std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

struct Flags {
  std::string address = "127.0.0.1";
  int port = 50051;
  std::string audio_out = "default";
  std::string audio_in = "default";
  std::string profile;  // empty: with a key the first profile that carries a MAC, else seed
  bool allow_unauthenticated = false;
  std::optional<std::string> db;
  std::string spill_file;
  std::string on_unconfirmed = "fail";
  double decision_timeout_s = 60;
  std::size_t max_queue = 32;
  std::string tls_cert, tls_key, auth_token_file;
  bool allow_anyone = false;
  dtmf::program::KeyFlags keys;
  int robot_address = 0;
  std::string robot = "burger";
  std::string robot_name = "robot";
  std::string robots_file;
  std::string host;  // this sender's name in the database; empty: the machine's
  dtmf::program::AudioProgramOptions program;
};

// Read before any device or database is opened, so that a refused combination costs nothing.
// The TLS key and the token are refused if others may read them, a blank token too (secret_file.h).
dtmf::server::ServerSecurity read_security(const Flags& f) {
  dtmf::server::ServerSecurity security = dtmf::server::read_security_files(f.tls_cert, f.tls_key, f.auth_token_file);
  security.allow_anyone_on_the_network = f.allow_anyone;
  return security;
}

// --profile, or with a key the first profile whose frames carry a MAC (fast), else the seed's.
// With a key, a profile without one needs --allow-unauthenticated-commands: a keyed robot
// refuses its frames, and anyone can play its ACK.
const dtmf::LinkProfile& default_profile(const Flags& f, const std::vector<std::unique_ptr<dtmf::link::Link>>& links) {
  if (f.profile.empty()) return dtmf::link::default_profile(links);
  const dtmf::LinkProfile& chosen = dtmf::profile_by_name(f.profile);
  for (const auto& l : links) {
    if (&l->profile() == &chosen && l->keyed() && !l->can_authenticate() && !f.allow_unauthenticated) {
      throw std::invalid_argument("--profile " + f.profile +
                                  ": carries no MAC, and this server has a key (--key): a keyed robot refuses its "
                                  "frames and anyone can play its ACK. Leave --profile out (commands then go "
                                  "authenticated), or add --allow-unauthenticated-commands");
    }
  }
  return chosen;
}

// The loudspeaker and the microphone. A file stands in for the loudspeaker in real time: gaps
// and retries keep their length. Opened real-time, so that the sound library's threads are too.
std::pair<std::unique_ptr<dtmf::physical::AudioSink>, std::unique_ptr<dtmf::physical::AudioSource>> open_audio(
    const Flags& f, const dtmf::LinkProfile& profile) {
  using namespace dtmf;
  const physical::AudioPriorityScope audio_priority;
  std::unique_ptr<physical::AudioSink> speaker =
      physical::is_file_spec(f.audio_out)
          ? std::make_unique<physical::RealTimeWavSink>(f.audio_out.substr(4), profile.sample_rate_hz)
          : physical::open_audio_sink(f.audio_out, profile.sample_rate_hz, f.program.devices);
  std::unique_ptr<physical::AudioSource> microphone =
      f.audio_in == "none" ? std::make_unique<Silence>(profile.sample_rate_hz)
                           : physical::open_audio_source(f.audio_in, profile.sample_rate_hz, 0, f.program.devices);
  spdlog::info("playing to {}, listening to {}", speaker->describe(), microphone->describe());
  return {std::move(speaker), std::move(microphone)};
}

// The gRPC server for `service`, with health, reflection and the UTF-8 check, serving; `port`
// the port it listens on.
std::unique_ptr<grpc::Server> start_serving(const Flags& f, const std::shared_ptr<grpc::ServerCredentials>& credentials,
                                            grpc::Service& service, int& port) {
  // gRPC's built-in health service carries no protobuf descriptors; touching one links
  // grpc.health.v1 into the generated pool, so that reflection can describe and call it.
  (void)grpc::health::v1::HealthCheckRequest::descriptor();
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(f.address + ":" + std::to_string(f.port), credentials, &port);
  builder.RegisterService(&service);
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(dtmf::server::utf8_refusal_interceptor());
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    throw std::runtime_error("cannot listen on " + f.address + ":" + std::to_string(f.port) +
                             " (is another server using the port? choose one with --port)");
  }
  server->GetHealthCheckService()->SetServingStatus(true);
  return server;
}

// The robots to drive: --robots FILE (read only if no one else may change it), else one robot
// from --robot-name, --robot-address, --key and --robot. Every key is read and told apart from
// the others and the room key before link_options() opens a counter store for any: one key
// named twice is refused for what it is, not for the lock the second store finds taken.
std::vector<dtmf::server::RobotLinks> robot_links(const Flags& f) {
  using namespace dtmf;
  const std::vector<server::RobotEntry> entries =
      f.robots_file.empty() ? std::vector<server::RobotEntry>{{f.robot_name, static_cast<std::uint8_t>(f.robot_address),
                                                               f.keys.key_file, f.robot}}
                            : server::read_robots(f.robots_file);
  server::check_keys_apart(entries, f.keys.room_key_file, f.robots_file.empty() ? "--key" : f.robots_file);
  std::vector<server::RobotLinks> robots;
  for (const server::RobotEntry& e : entries) {
    program::KeyFlags keys = f.keys;
    keys.key_file = e.key_file;
    server::RobotLinks r;
    r.name = e.name;
    r.model = command::robot_model_by_name(e.model);
    r.links = link::make_links(program::link_options(keys, e.address));
    if (!f.robots_file.empty()) {
      spdlog::info("robot {}: address {}, {}, {}", server::shown(e.name), e.address,
                   e.key_file.empty() ? "no key" : "key " + server::shown(e.key_file), e.model);
    }
    robots.push_back(std::move(r));
  }
  return robots;
}

int run(const Flags& f) {
  using namespace dtmf;
  const server::ServerSecurity security = read_security(f);
  const std::shared_ptr<grpc::ServerCredentials> credentials = server::server_credentials(security, f.address);
  if (server::open_to_anyone(security, f.address)) {
    spdlog::warn(
        "serving {} without TLS and a bearer token (--allow-anyone-on-the-network): anyone who can reach "
        "port {} can drive the robot",
        f.address, f.port);
  }
  // The keys before any device: a key file others may read stops the server here.
  std::vector<server::RobotLinks> robots = robot_links(f);
  std::vector<std::unique_ptr<link::Link>> room_links = link::make_links(program::room_link_options(f.keys));
  // The default profile: a keyed robot's, if any robot has a key (fast, authenticated); with
  // several robots, one whose frames name the robot (fast).
  const auto keyed = std::find_if(robots.begin(), robots.end(), [](const auto& r) { return r.links.front()->keyed(); });
  const auto& default_links = (keyed != robots.end() ? *keyed : robots.front()).links;
  const auto addressed =
      std::find_if(default_links.begin(), default_links.end(), [](const auto& l) { return l->addresses_robots(); });
  const LinkProfile& profile = robots.size() > 1 && f.profile.empty() && addressed != default_links.end()
                                   ? (*addressed)->profile()
                                   : default_profile(f, default_links);
  if (keyed == robots.end()) {
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
  auto [speaker, microphone] = open_audio(f, profile);

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
  const std::unique_ptr<grpc::Server> grpc_server = start_serving(f, credentials, service, port);
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
  Flags f;
  CLI::App app{"dtmf-server: the gRPC control API that drives a TurtleBot3 by sound"};
  app.add_option("--address", f.address,
                 "address to listen on; off this machine only with TLS and a token, or --allow-anyone-on-the-network")
      ->envname("DTMF_SERVER_ADDRESS")
      ->capture_default_str();
  app.add_option("--port", f.port, "port to listen on (0: any free one)")
      ->check(CLI::Range(0, 65535))
      ->envname("DTMF_SERVER_PORT")
      ->capture_default_str();
  app.add_option("--audio-out", f.audio_out,
                 "loudspeaker: a device name or index, default, or wav:FILE (write what would be played)")
      ->envname("DTMF_SERVER_AUDIO_OUT")
      ->capture_default_str();
  app.add_option("--audio-in", f.audio_in,
                 "microphone for the robot's ACK / NACK: a device, default, wav:FILE, or none")
      ->envname("DTMF_SERVER_AUDIO_IN")
      ->capture_default_str();
  app.add_option("--profile", f.profile,
                 "link profile of commands that name none (CommandOptions.profile): " + dtmf::profile_names() +
                     "; default: with --key the first that carries a MAC (fast), else seed")
      ->envname("DTMF_SERVER_PROFILE");
  app.add_flag("--allow-unauthenticated-commands", f.allow_unauthenticated,
               "with --key: let commands name a profile without a MAC (seed); their untagged ACKs are reported as "
               "unauthenticated (a warning at every start). Stop always goes authenticated")
      ->envname("DTMF_SERVER_ALLOW_UNAUTHENTICATED_COMMANDS");
  app.add_option("--db", f.db,
                 "PostgreSQL URL, or none; default: DTMF_DB_URL, else the libpq environment (PGHOST, ...)")
      ->envname("DTMF_DB_URL");
  app.add_option("--spill-file", f.spill_file, "where log rows wait while the database is away");
  app.add_option("--host", f.host,
                 "name of this sender in the database (default: hostname); give each server in a room its own")
      ->envname("DTMF_SERVER_HOST");
  app.add_option("--on-unconfirmed", f.on_unconfirmed,
                 "default policy for a frame unconfirmed after the automatic retry")
      ->check(CLI::IsMember({"ask", "continue", "fail"}))
      ->capture_default_str();
  app.add_option("--decision-timeout-s", f.decision_timeout_s, "with ask: how long to wait for Decide")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  app.add_option("--max-queue", f.max_queue, "commands that may wait; more get RESOURCE_EXHAUSTED")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app.add_option("--tls-cert", f.tls_cert, "PEM certificate: serve TLS (with --tls-key)")
      ->envname("DTMF_SERVER_TLS_CERT");
  app.add_option("--tls-key", f.tls_key, "PEM private key")->envname("DTMF_SERVER_TLS_KEY");
  app.add_option("--auth-token-file", f.auth_token_file,
                 "every call must carry 'authorization: Bearer <token in this file>'")
      ->envname("DTMF_SERVER_AUTH_TOKEN_FILE");
  app.add_flag("--allow-anyone-on-the-network", f.allow_anyone,
               "serve an address off this machine without TLS and a token: anyone who reaches the port can drive "
               "the robot (a warning at start)")
      ->envname("DTMF_SERVER_ALLOW_ANYONE_ON_THE_NETWORK");
  dtmf::program::add_key_flags(app, f.keys, "DTMF_SERVER", "/var/lib/dtmf-server");
  dtmf::program::add_room_key_flag(app, f.keys, "DTMF_SERVER");
  auto* robots = app.add_option("--robots", f.robots_file,
                                "several robots: a JSON list of {name, address, key, model} (docs/protocol.md §9); "
                                "instead of --robot-name, --robot-address, --key and --robot")
                     ->envname("DTMF_SERVER_ROBOTS_FILE")
                     ->check(CLI::ExistingFile);
  app.add_option("--robot-name", f.robot_name, "the one robot's name (commands name it: dtmfctl --robot)")
      ->envname("DTMF_SERVER_ROBOT_NAME")
      ->check([](const std::string& name) {
        return dtmf::server::robot_name_valid(name) ? std::string() : "1 to 32 letters, digits, - or _";
      })
      ->capture_default_str()
      ->excludes(robots);
  app.add_option("--robot-address", f.robot_address, "the robot's address (0..7, dtmf-agent --address)")
      ->envname("DTMF_SERVER_ROBOT_ADDRESS")
      ->check(CLI::Range(0, 7))
      ->capture_default_str()
      ->excludes(robots);
  app.get_option("--key")->excludes(robots);
  app.add_option("--robot", f.robot,
                 "TurtleBot3 model driven (as dtmf-agent --robot): Teleop's speeds are fractions of its limits")
      ->envname("TURTLEBOT3_MODEL")
      ->check(CLI::IsMember({"burger", "waffle", "waffle_pi"}))
      ->capture_default_str();
  dtmf::program::add_audio_program_options(app, f.program);
  f.program.without_devices =
      "or run without a sound card: --audio-out wav:FILE --audio-in none (scripts/air start "
      "gives a private PulseAudio)";
  app.footer(
      "Exit codes: 0 stopped cleanly, 1 an audio device, the database or the port could not be had, 2 bad usage.\n"
      "SIGINT / SIGTERM: health goes NOT_SERVING, the chord on air finishes, queued commands end UNAVAILABLE.");
  return dtmf::program::audio_program_main(app, argc, argv, f.program, [&] { return run(f); });
}
