// Test fixture: the whole system in one process. The server's transmitter and the robot's
// agent talk through a simulated room running in real time (sim/simulated_air.h); the
// service listens on a loopback port for real gRPC clients.
#pragma once

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "agent.h"
#include "dtmf/v1/teleop.grpc.pb.h"
#include "sim/simulated_air.h"
#include "store_recorder.h"
#include "teleop_service.h"

namespace dtmf::test_support {

struct LiveSystemOptions {
  // The server's default (none: as dtmf-server's, fast with a key, else seed); the robot hears every profile.
  const LinkProfile* profile = nullptr;
  bool allow_unauthenticated = false;  // dtmf-server --allow-unauthenticated-commands
  double distance_m = 1.0;
  double air_block_ms = 10;   // the room's audio period: what a device buffer adds to each way
  std::string rir_file;       // a measured room both ways (pink noise -50 dBFS); empty: free field, white -70 dBFS
  bool robot_answers = true;  // false: the robot's loudspeaker is dead (every ACK lost)
  std::string auth_token;
  std::size_t max_queue = 32;
  bool listen_before_talk = true;               // the sender's (server::TransmitterOptions)
  store::DatabaseUrl database = std::string();  // none
  server::Policy default_policy = server::Policy::Fail;
  // Keys of the sender and of the robot (none: unauthenticated); each side keeps its
  // counters in memory, the robot's starting with none accepted.
  std::shared_ptr<const security::LinkKey> sender_key;
  std::shared_ptr<const security::LinkKey> robot_key;
  bool robot_accepts_unauthenticated = false;  // dtmf-agent --accept-unauthenticated
  // A third loudspeaker in the room, 0.3 m from the sender's microphone (a stranger's
  // phone): forger_speaker() plays what a test gives it.
  bool forger = false;
  // Called with each progress event the transmitter emits, before it is recorded, on the
  // transmitter's threads (Queued: the submitting caller's). A test may throw from it on a
  // Queued event: the transmitter's submit() then refuses the command (Refusal::Unrecorded,
  // naming what it threw).
  std::function<void(const server::ProgressEvent&)> before_recording;
};

// What the robot heard, in order: seed words of intact frames, and commands executed.
struct HeardWords {
  std::mutex mutex;
  std::vector<int> words;
  std::vector<std::string> commands;
  int intact_frames = 0;   // of every profile, repeats included
  int refused_frames = 0;  // intact, but refused (authentication, payload)
};

// One cmd_vel sample the robot published, and when (the agent runs in real time).
struct PublishedVelocity {
  std::chrono::steady_clock::time_point at;
  agent::Velocity velocity;
};

class LiveSystem {
 public:
  explicit LiveSystem(LiveSystemOptions options = {});
  ~LiveSystem();

  std::unique_ptr<v1::TeleopService::Stub> client() const;
  std::shared_ptr<grpc::Channel> channel() const { return channel_; }
  int port() const { return port_; }
  std::vector<int> words_heard();
  std::vector<std::string> commands_executed();
  int intact_frames_heard();
  int refused_frames_heard();
  agent::Velocity last_velocity();
  // Every cmd_vel sample so far, in order, from the `from`th on (the history only grows).
  std::vector<PublishedVelocity> velocities(std::size_t from = 0);
  // How the sender shared the air: a lone sender defers to no one and never yields.
  server::AirShare air_share() const { return transmitter_->air_share(); }
  // Who watches the sender's air now (WatchAir streams among them).
  std::size_t air_watchers() const { return transmitter_->air_events().watchers(); }
  // The sound devices go away (a USB sound card unplugged): the room stops.
  void pull_the_plug() { air_.stop(); }
  // The sender's loudspeaker goes silent (or sounds again): the link is lost from now on, the
  // frame on air cut where it is; the server goes on as if nothing happened.
  void mute_sender(bool muted) { air_.mute("sender", muted); }
  // The forger's loudspeaker (LiveSystemOptions::forger): its write() returns once the
  // samples are queued close to playing, like a sound card's.
  physical::AudioSink& forger_speaker() { return *forger_speaker_; }

 private:
  class Recorder;
  class SendObserver;
  LiveSystemOptions options_;
  HeardWords heard_;
  sim::SimulatedAir air_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<server::StoreRecorder> recorder_of_sends_;
  std::unique_ptr<SendObserver> send_observer_;
  std::unique_ptr<server::Transmitter> transmitter_;
  std::unique_ptr<server::TeleopService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  int port_ = 0;
  // The robot.
  std::unique_ptr<physical::AudioSource> robot_microphone_;
  std::unique_ptr<agent::ReplyPlayer> robot_replies_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<store::Store> robot_store_;
  std::unique_ptr<agent::Timeline> timeline_;
  std::unique_ptr<agent::Agent> agent_;
  std::atomic<bool> stopping_{false};
  std::thread robot_;
  std::unique_ptr<physical::AudioSink> forger_speaker_;
};

// Reads a server stream to its end: every response, and the final status.
template <class Response>
struct StreamResult {
  std::vector<Response> responses;
  grpc::Status status;
};

template <class Response, class Start>
StreamResult<Response> read_stream(Start start, const std::string& token = "",
                                   const std::function<void(const Response&)>& on_response = {}) {
  grpc::ClientContext context;
  if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
  StreamResult<Response> result;
  auto reader = start(context);
  Response response;
  while (reader->Read(&response)) {
    result.responses.push_back(response);
    if (on_response) on_response(response);
  }
  result.status = reader->Finish();
  return result;
}

// A server stream read on its own thread, so that a test waits for the command's progress
// (QUEUED, TRANSMITTING) instead of sleeping and assuming it got there.
template <class Response>
class BackgroundStream {
 public:
  // `start(context)` begins the call, on the stream's own thread, with its own client.
  template <class Start>
  explicit BackgroundStream(Start start) {
    result_ = std::async(std::launch::async, [this, start] {
      return read_stream<Response>(start, "", [this](const Response& r) {
        {
          std::lock_guard lock(mutex_);
          events_.push_back(r.progress().event());
        }
        changed_.notify_all();
      });
    });
  }
  ~BackgroundStream() {
    if (result_.valid()) result_.wait();
  }
  // True once the stream has carried `event`; false if `within` passed first.
  bool wait_for(v1::FrameEvent event, std::chrono::milliseconds within = std::chrono::seconds(30)) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, within,
                             [&] { return std::find(events_.begin(), events_.end(), event) != events_.end(); });
  }
  StreamResult<Response> finish() { return result_.get(); }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<v1::FrameEvent> events_;
  std::future<StreamResult<Response>> result_;  // last: its thread uses the members above
};

}  // namespace dtmf::test_support
