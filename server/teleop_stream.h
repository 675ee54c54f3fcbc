// One Teleop call (TeleopService::Teleop) as a small reactor, in the manner of gRPC's
// route_guide callback server: no thread, no sleep, no poll. Its first message opens it (the
// service checks it and takes the robot's slot: one stream drives a robot at a time); then it
// sends the newest target one frame at a time through the transmitter (Policy::Live: once, no
// retransmission), answering with the status after each of the frame's events.
// teleop_session.h holds the rules; this is the I/O. Its inputs: a message read, a write
// done, the client's cancel, a frame's event, a Stop's halt, and the time the session's rules
// next change (reactor_steps.h runs its step at each). Every way out goes through one end: the
// frame in flight cancelled (a chord on air completes), renewals stopped, a last FAILED status
// for a failure, the slot released, then Finish (so a client told the stream ended finds the
// robot free).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <variant>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "reactor_steps.h"
#include "teleop_session.h"
#include "transmitter.h"

namespace dtmf::server {

// The session's time scale (teleop_session.h): seconds of the steady clock.
inline double steady_s(std::chrono::steady_clock::time_point at = std::chrono::steady_clock::now()) {
  return std::chrono::duration<double>(at.time_since_epoch()).count();
}

// The teleop slot: one stream drives at a time. Held for the life of this object.
class TeleopSlot {
 public:
  // Claims the slot for `session`; held() is false if another stream holds it.
  TeleopSlot(std::mutex& mutex, std::weak_ptr<TeleopSession>& holder, const std::shared_ptr<TeleopSession>& session);
  ~TeleopSlot();
  TeleopSlot(const TeleopSlot&) = delete;
  TeleopSlot& operator=(const TeleopSlot&) = delete;
  bool held() const { return held_; }

 private:
  std::mutex& mutex_;
  std::weak_ptr<TeleopSession>& holder_;
  bool held_ = false;
};

struct TeleopStreamSetup {
  const LinkProfile* profile = nullptr;
  RobotIndex robot = 0;
  std::chrono::milliseconds decision_timeout{0};
  double carried_lease_s = 0;      // the lease as the frames carry it
  command::Velocity first_target;  // the first message's
  double first_lease_s = 0;        // the stream's lease: the first message's
  // A request's target; throws RequestError naming the field.
  std::function<command::Velocity(const v1::TeleopRequest&)> target_of;
};

// What the first message opened: the stream's rules, its slot and its setup.
struct TeleopOpened {
  std::shared_ptr<TeleopSession> session;
  std::unique_ptr<TeleopSlot> slot;
  TeleopStreamSetup setup;
};
// Checks the first message and takes the slot; the status that refuses it otherwise.
using TeleopOpener = std::function<std::variant<TeleopOpened, grpc::Status>(const v1::TeleopRequest& first)>;

class TeleopReactor final : public grpc::ServerBidiReactor<v1::TeleopRequest, v1::TeleopResponse> {
 public:
  // Reads the first message; gRPC owns the returned reactor until OnDone.
  static TeleopReactor* start(Transmitter& transmitter, TeleopOpener open);

  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  TeleopReactor(Transmitter& transmitter, TeleopOpener open);
  void opened(const v1::TeleopRequest& first);

  // The step (teleop_stream_step.cpp): follows the frame in flight, renews, sends the next
  // frame due, or ends; then waits for the session's next change.
  void step();
  // Why the stream must end now, if it must.
  std::optional<grpc::Status> end_due(double now_s);
  // Writes the frame's next event; true once the frame ended (and was followed to its end).
  bool follow_frame(double now_s);
  void follow_renewals(double now_s);
  void send_frame(const command::Velocity& velocity);
  void write_status(const v1::Progress* progress);
  void end_step();
  void wait_for_change(double now_s);

  Transmitter& transmitter_;
  TeleopOpener open_;
  std::shared_ptr<TeleopReactor> self_;  // held until OnDone
  std::optional<ReactorSteps> steps_;
  v1::TeleopRequest request_;

  // Set once, by the first message, before `opened_` (under the lock) says so.
  std::shared_ptr<TeleopSession> session_;
  std::unique_ptr<TeleopSlot> slot_;
  TeleopStreamSetup setup_;

  // The step's own.
  std::shared_ptr<Job> job_;  // the frame in flight, if any
  bool answered_ = false;     // ... and what was heard of it
  bool confirmed_ = false;
  double response_ms_ = 0;
  bool renewing_ = false;  // kept renewed by the transmitter (Transmitter::keep_renewed)
  std::optional<grpc::Status> ending_;
  bool failure_written_ = false;
  bool finished_ = false;
  v1::TeleopResponse response_;

  // The reactions', under the lock.
  std::mutex mutex_;
  bool opened_ = false;
  bool writing_ = false;
  bool cancelled_ = false;
  std::optional<grpc::Status> refused_;  // the first message refused, or a bad target mid-stream
  bool closed_unopened_ = false;         // the client closed before its first message
};

}  // namespace dtmf::server
