// One robot's Teleop stream, as a gRPC callback reactor: the loop writes targets and closes
// it; gRPC's threads push what the server answers, and the stream's end, to BridgeEvents.
//
// Newest wins here too: a target written while another is still being sent replaces any
// that waits. A hold keeps the call from finishing while the loop may still write; it is
// released once, when the loop has closed the stream or the server has ended it (a read
// fails), and the call then ends with the server's status (BridgeEvent::TeleopEnded). Only
// after that event may the owner destroy the call.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "bridge_events.h"
#include "dtmf/v1/teleop.grpc.pb.h"
#include "twist_input.h"

namespace dtmf::ros_bridge {

struct TeleopCallOptions {
  std::string robot;
  std::string profile;
  double lease_s = 1.0;
  std::string token;  // the server's bearer token; empty: none
};

class TeleopCall final : public grpc::ClientBidiReactor<v1::TeleopRequest, v1::TeleopResponse> {
 public:
  TeleopCall(v1::TeleopService::Stub& stub, const TeleopCallOptions& options, Twist first, BridgeEvents& events,
             std::size_t robot_index, std::uint64_t call_id);

  void write(Twist target);
  void close();   // WritesDone: the server ends the stream, its robot's lease lapses
  void cancel();  // when the bridge must go and the server does not answer

  void OnWriteDone(bool ok) override;
  void OnWritesDoneDone(bool ok) override;
  void OnReadDone(bool ok) override;
  void OnDone(const grpc::Status& status) override;

 private:
  v1::TeleopRequest request_for(Twist target) const;
  void release_locked();

  grpc::ClientContext context_;
  TeleopCallOptions options_;
  BridgeEvents& events_;
  std::size_t robot_index_;
  std::uint64_t call_id_;
  v1::TeleopResponse response_;

  std::mutex mutex_;
  v1::TeleopRequest in_flight_;
  std::optional<v1::TeleopRequest> waiting_;
  bool writing_ = false;
  bool close_asked_ = false;
  bool released_ = false;
};

}  // namespace dtmf::ros_bridge
