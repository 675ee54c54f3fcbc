// One Teleop call (TeleopService::Teleop) as a small class: it holds the teleop slot, owns
// the thread that reads the client's targets, and sends the newest target one frame at a
// time through the transmitter (Policy::Live: once, no retransmission), answering with the
// status after each frame's event. teleop_session.h holds the rules; this is the I/O.
//
// Every path out ends the same way, whatever was thrown: drive() turns any exception into a
// status (the server never terminates on a stream), and the destructor ends the stream,
// waits for the reader (for the client's next message, at most kReaderGrace, then cancels
// the call so that its Read returns) and joins it, and releases the slot. The sync API
// reads on a thread of its own because a blocking Read cannot be woken otherwise; the
// reader signals its end through a future, so nothing polls.
#pragma once

#include <grpcpp/grpcpp.h>

#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "teleop_session.h"
#include "transmitter.h"

namespace dtmf::server {

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

class TeleopStream {
 public:
  using Stream = grpc::ServerReaderWriter<v1::TeleopResponse, v1::TeleopRequest>;

  // Gives the session the first target and starts the reader.
  TeleopStream(grpc::ServerContext& context, Stream& stream, std::shared_ptr<TeleopSession> session,
               Transmitter& transmitter, TeleopStreamSetup setup);
  ~TeleopStream();
  TeleopStream(const TeleopStream&) = delete;
  TeleopStream& operator=(const TeleopStream&) = delete;

  // Sends frames until the stream ends, is cancelled or halted, or fails; never throws.
  grpc::Status drive();

 private:
  void read_targets();
  grpc::Status drive_frames();
  // Keeps the robot renewed jointly while the session is renewable (fast links), and tells
  // the session when a renewal renewed it.
  void follow_renewals();
  // Sends one frame and streams its events; a status if the stream must end.
  std::optional<grpc::Status> send_frame(const command::Velocity& velocity);
  bool write_status(const v1::Progress* progress);
  void write_failure(const grpc::Status& status);

  grpc::ServerContext& context_;
  Stream& stream_;
  std::shared_ptr<TeleopSession> session_;
  Transmitter& transmitter_;
  TeleopStreamSetup setup_;
  std::shared_ptr<Job> job_;  // the frame on air, if any
  bool renewing_ = false;     // kept renewed by the transmitter (Transmitter::keep_renewed)
  std::mutex refused_mutex_;
  std::optional<grpc::Status> refused_;  // a bad target mid-stream, or the reader's failure
  std::promise<void> reader_done_;
  std::future<void> reader_finished_ = reader_done_.get_future();
  std::thread reader_;
};

}  // namespace dtmf::server
