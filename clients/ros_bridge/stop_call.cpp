#include "stop_call.h"

namespace dtmf::ros_bridge {

StopCall::StopCall(v1::TeleopService::Stub& stub, const std::string& profile, const std::string& token,
                   BridgeEvents& events)
    : events_(events) {
  if (!token.empty()) context_.AddMetadata("authorization", "Bearer " + token);
  context_.AddMetadata("x-dtmf-client", kBridgeClientName);
  request_.set_all_robots(true);
  request_.mutable_options()->set_profile(profile);
  stub.async()->Stop(&context_, &request_, this);
  StartRead(&response_);
  StartCall();
}

void StopCall::OnReadDone(bool ok) {
  if (ok) StartRead(&response_);
}

void StopCall::OnDone(const grpc::Status& status) { events_.push({BridgeEvent::Kind::StopEnded, 0, 0, {}, status}); }

}  // namespace dtmf::ros_bridge
