// The stop for every robot (Stop with all_robots), as a gRPC callback reactor: it reads the
// progress to its end and pushes BridgeEvent::StopEnded. Only after that event may the owner
// destroy it. The server plays it before anything else, and it ends every Teleop stream.
#pragma once

#include <grpcpp/grpcpp.h>

#include <string>

#include "bridge_events.h"
#include "dtmf/v1/teleop.grpc.pb.h"

namespace dtmf::ros_bridge {

class StopCall final : public grpc::ClientReadReactor<v1::StopResponse> {
 public:
  StopCall(v1::TeleopService::Stub& stub, const std::string& profile, const std::string& token, BridgeEvents& events);
  void cancel() { context_.TryCancel(); }

  void OnReadDone(bool ok) override;
  void OnDone(const grpc::Status& status) override;

 private:
  grpc::ClientContext context_;
  v1::StopRequest request_;
  v1::StopResponse response_;
  BridgeEvents& events_;
};

}  // namespace dtmf::ros_bridge
