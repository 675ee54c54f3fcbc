#include "live_system.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include "bearer_token_auth.h"

namespace dtmf::test_support {

class LiveSystem::SendObserver : public server::ProgressObserver {
 public:
  SendObserver(server::ProgressObserver& next, std::function<void(const server::ProgressEvent&)> before)
      : next_(next), before_(std::move(before)) {}
  void observe(const server::Job& job, const server::ProgressEvent& event) override {
    if (before_) before_(event);
    next_.observe(job, event);
  }

 private:
  server::ProgressObserver& next_;
  std::function<void(const server::ProgressEvent&)> before_;
};

namespace {
class Mute : public agent::ReplyPlayer {
 public:
  void play(std::vector<float>, double) override {}
  void finish(double) override {}
};
}  // namespace

class LiveSystem::Recorder : public agent::CmdVelOutput {
 public:
  void publish(const agent::Velocity& v, double, std::chrono::system_clock::time_point) override {
    std::lock_guard lock(mutex);
    last = v;
    history.push_back({std::chrono::steady_clock::now(), v});
  }
  std::mutex mutex;
  agent::Velocity last;
  std::vector<PublishedVelocity> history;
};

namespace {

LiveSystemOptions with_profile(LiveSystemOptions options) {
  if (!options.profile) {
    link::LinkOptions keyed;
    keyed.key = options.sender_key;
    options.profile = &link::default_profile(link::make_links(keyed));
  }
  return options;
}

}  // namespace

LiveSystem::LiveSystem(LiveSystemOptions options)
    : options_(with_profile(std::move(options))),
      air_(
          options_.profile->sample_rate_hz,
          [this] {
            sim::ChannelConfig air;
            air.noise = options_.rir_file.empty() ? sim::parse_noise("white", -70) : sim::parse_noise("pink", -50);
            air.room.rir_file = options_.rir_file;
            return air;
          }(),
          options_.air_block_ms) {
  const LinkProfile& profile = *options_.profile;
  auto sender = air_.add_station("sender", 0.0);
  auto robot = air_.add_station("robot", options_.distance_m);
  if (options_.forger) forger_speaker_ = air_.add_station("forger", -0.3).speaker;
  air_.start();

  store::StoreOptions no_db;
  no_db.database = std::string();
  robot_store_ = std::make_unique<store::Store>(no_db);
  robot_microphone_ = std::move(robot.microphone);
  if (options_.robot_answers)
    robot_replies_ = std::make_unique<agent::LiveReplyPlayer>(std::move(robot.speaker), std::chrono::milliseconds(0));
  else
    robot_replies_ = std::make_unique<Mute>();
  recorder_ = std::make_unique<Recorder>();
  timeline_ = std::make_unique<agent::Timeline>(true);
  agent::AgentOptions agent_options;
  agent_options.profiles = all_profiles();
  agent_options.link.key = options_.robot_key;
  agent_options.link.accept_unauthenticated = options_.robot_accepts_unauthenticated;
  agent_options.on_frame_heard = [this](const agent::HeardFrame& frame) {
    const link::Reception& r = frame.reception;
    if (!r.intact) return;
    std::lock_guard lock(heard_.mutex);
    ++heard_.intact_frames;
    if (r.event == link::ReceptionEvent::Refused) ++heard_.refused_frames;
    if (r.payload_word) heard_.words.push_back(*r.payload_word);
    if (frame.executed) heard_.commands.push_back(command::describe(*frame.executed));
  };
  agent_ = std::make_unique<agent::Agent>(
      agent_options, *robot_replies_, std::vector<agent::CmdVelOutput*>{recorder_.get()}, *robot_store_, *timeline_);
  robot_ = std::thread([this] {
    std::vector<float> block(static_cast<std::size_t>(agent_->block_samples()));
    while (!stopping_) {
      const std::size_t got = robot_microphone_->read(block);
      if (got == 0) return;
      agent_->process(std::span<const float>(block.data(), got));
    }
  });

  store::StoreOptions server_db;
  server_db.database = options_.database;
  server_db.spill_path = ::testing::TempDir() + "/live-system-" + std::to_string(::getpid()) + ".spill";
  store_ = std::make_unique<store::Store>(server_db);
  recorder_of_sends_ = std::make_unique<server::StoreRecorder>(*store_, "test");
  send_observer_ = std::make_unique<SendObserver>(*recorder_of_sends_, options_.before_recording);
  link::LinkOptions sender_links;
  sender_links.key = options_.sender_key;
  transmitter_ = std::make_unique<server::Transmitter>(
      link::make_links(sender_links), profile, std::move(sender.speaker), std::move(sender.microphone), *send_observer_,
      server::TransmitterOptions{.max_queue = options_.max_queue,
                                 .allow_unauthenticated = options_.allow_unauthenticated,
                                 .listen_before_talk = options_.listen_before_talk});
  server::ServiceOptions service_options;
  service_options.database = options_.database;
  service_options.defaults.policy = options_.default_policy;
  service_ = std::make_unique<server::TeleopService>(*transmitter_, *store_, service_options);
  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  server::ServerSecurity security;
  security.auth_token = options_.auth_token;
  builder.AddListeningPort("127.0.0.1:0", server::server_credentials(security, "127.0.0.1"), &port_);
  builder.RegisterService(service_.get());
  server_ = builder.BuildAndStart();
  channel_ = grpc::CreateChannel("127.0.0.1:" + std::to_string(port_), grpc::InsecureChannelCredentials());
}

LiveSystem::~LiveSystem() {
  transmitter_->shutdown();
  server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  stopping_ = true;
  air_.stop();
  robot_.join();
}

std::unique_ptr<v1::TeleopService::Stub> LiveSystem::client() const { return v1::TeleopService::NewStub(channel_); }

std::vector<int> LiveSystem::words_heard() {
  std::lock_guard lock(heard_.mutex);
  return heard_.words;
}

int LiveSystem::intact_frames_heard() {
  std::lock_guard lock(heard_.mutex);
  return heard_.intact_frames;
}

int LiveSystem::refused_frames_heard() {
  std::lock_guard lock(heard_.mutex);
  return heard_.refused_frames;
}

std::vector<std::string> LiveSystem::commands_executed() {
  std::lock_guard lock(heard_.mutex);
  return heard_.commands;
}

agent::Velocity LiveSystem::last_velocity() {
  std::lock_guard lock(recorder_->mutex);
  return recorder_->last;
}

std::vector<PublishedVelocity> LiveSystem::velocities(std::size_t from) {
  std::lock_guard lock(recorder_->mutex);
  if (from >= recorder_->history.size()) return {};
  return {recorder_->history.begin() + static_cast<std::ptrdiff_t>(from), recorder_->history.end()};
}

}  // namespace dtmf::test_support
