// dtmf-server's parts from its flags (server_setup.h): each reads or opens one thing, logs
// what it found, and throws with the way out when it cannot be had.
#include "server_setup.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>

#include <spdlog/spdlog.h>
#include <algorithm>
#include <chrono>
#include <thread>

#include "grpc/health/v1/health.pb.h"
#include "physical/audio_spec.h"
#include "physical/portaudio_device.h"
#include "physical/realtime_priority.h"
#include "physical/wav_file.h"
#include "robot_roster.h"
#include "secret_file.h"
#include "shown_text.h"
#include "utf8_refusal.h"

namespace dtmf::server {

namespace {

// --audio-in none: a microphone that hears silence, in real time.
class Silence : public physical::AudioSource {
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

// --profile, or with a key the first profile whose frames carry a MAC (fast), else the seed's.
// With a key, a profile without one needs --allow-unauthenticated-commands: a keyed robot
// refuses its frames, and anyone can play its ACK.
const LinkProfile& flagged_profile(const ServerFlags& f, const std::vector<std::unique_ptr<link::Link>>& links) {
  if (f.profile.empty()) return link::default_profile(links);
  const LinkProfile& chosen = profile_by_name(f.profile);
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

}  // namespace

// Read before any device or database is opened, so that a refused combination costs nothing.
ServerSecurity read_security(const ServerFlags& f) {
  ServerSecurity security = read_security_files(f.tls_cert, f.tls_key, f.auth_token_file);
  security.allow_anyone_on_the_network = f.allow_anyone;
  return security;
}

// Every key is read and told apart from the others and the room key before link_options()
// opens a counter store for any: one key named twice is refused for what it is, not for the
// lock the second store finds taken. The robots file is read only if no one else may change it.
std::vector<RobotLinks> robot_links(const ServerFlags& f) {
  const std::vector<RobotEntry> entries =
      f.robots_file.empty() ? std::vector<RobotEntry>{{f.robot_name, static_cast<std::uint8_t>(f.robot_address),
                                                       f.keys.key_file, f.robot}}
                            : read_robots(f.robots_file);
  check_keys_apart(entries, f.keys.room_key_file, f.robots_file.empty() ? "--key" : f.robots_file);
  std::vector<RobotLinks> robots;
  for (const RobotEntry& e : entries) {
    program::KeyFlags keys = f.keys;
    keys.key_file = e.key_file;
    RobotLinks r;
    r.name = e.name;
    r.model = command::robot_model_by_name(e.model);
    r.links = link::make_links(program::link_options(keys, e.address));
    if (!f.robots_file.empty()) {
      spdlog::info("robot {}: address {}, {}, {}", shown(e.name), e.address,
                   e.key_file.empty() ? "no key" : "key " + shown(e.key_file), e.model);
    }
    robots.push_back(std::move(r));
  }
  return robots;
}

// A keyed robot's links decide, if any robot has a key (fast, authenticated); with several
// robots and no --profile, a profile whose frames name the robot (fast).
const LinkProfile& default_profile(const ServerFlags& f, const std::vector<RobotLinks>& robots) {
  const auto keyed = std::find_if(robots.begin(), robots.end(), [](const auto& r) { return r.links.front()->keyed(); });
  const auto& default_links = (keyed != robots.end() ? *keyed : robots.front()).links;
  const auto addressed =
      std::find_if(default_links.begin(), default_links.end(), [](const auto& l) { return l->addresses_robots(); });
  return robots.size() > 1 && f.profile.empty() && addressed != default_links.end() ? (*addressed)->profile()
                                                                                    : flagged_profile(f, default_links);
}

// A file stands in for the loudspeaker in real time: gaps and retries keep their length.
// Opened real-time, so that the sound library's threads are too.
std::pair<std::unique_ptr<physical::AudioSink>, std::unique_ptr<physical::AudioSource>> open_audio(
    const ServerFlags& f, const LinkProfile& profile) {
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

std::unique_ptr<grpc::Server> start_serving(const ServerFlags& f,
                                            const std::shared_ptr<grpc::ServerCredentials>& credentials,
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
  interceptors.push_back(utf8_refusal_interceptor());
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    throw std::runtime_error("cannot listen on " + f.address + ":" + std::to_string(f.port) +
                             " (is another server using the port? choose one with --port)");
  }
  server->GetHealthCheckService()->SetServingStatus(true);
  return server;
}

}  // namespace dtmf::server
