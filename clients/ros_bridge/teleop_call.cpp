#include "teleop_call.h"

namespace dtmf::ros_bridge {

TeleopCall::TeleopCall(v1::TeleopService::Stub& stub, const TeleopCallOptions& options, Twist first,
                       BridgeEvents& events, std::size_t robot_index, std::uint64_t call_id)
    : options_(options), events_(events), robot_index_(robot_index), call_id_(call_id) {
  if (!options.token.empty()) context_.AddMetadata("authorization", "Bearer " + options.token);
  context_.AddMetadata("x-dtmf-client", kBridgeClientName);
  stub.async()->Teleop(&context_, this);
  AddHold();
  in_flight_ = request_for(first);
  in_flight_.mutable_options()->set_profile(options.profile);
  in_flight_.mutable_options()->set_robot(options.robot);
  writing_ = true;
  StartWrite(&in_flight_);
  StartRead(&response_);
  StartCall();
}

v1::TeleopRequest TeleopCall::request_for(Twist target) const {
  v1::TeleopRequest request;
  request.set_linear_mps(target.linear_mps);
  request.set_angular_radps(target.angular_radps);
  request.set_lease_s(options_.lease_s);
  return request;
}

void TeleopCall::write(Twist target) {
  std::lock_guard lock(mutex_);
  if (released_ || close_asked_) return;
  if (writing_) {
    waiting_ = request_for(target);
    return;
  }
  in_flight_ = request_for(target);
  writing_ = true;
  StartWrite(&in_flight_);
}

void TeleopCall::close() {
  std::lock_guard lock(mutex_);
  if (released_ || close_asked_) return;
  close_asked_ = true;
  waiting_.reset();
  if (!writing_) StartWritesDone();
}

void TeleopCall::cancel() { context_.TryCancel(); }

void TeleopCall::release_locked() {
  if (released_) return;
  released_ = true;
  RemoveHold();
}

void TeleopCall::OnWriteDone(bool ok) {
  std::lock_guard lock(mutex_);
  writing_ = false;
  if (!ok || released_) return;  // the stream broke: the read fails too, and releases the hold
  if (waiting_) {
    in_flight_ = std::move(*waiting_);
    waiting_.reset();
    writing_ = true;
    StartWrite(&in_flight_);
  } else if (close_asked_) {
    StartWritesDone();
  }
}

void TeleopCall::OnWritesDoneDone(bool /*ok*/) {
  std::lock_guard lock(mutex_);
  release_locked();
}

void TeleopCall::OnReadDone(bool ok) {
  if (ok) {
    events_.push({BridgeEvent::Kind::TeleopResponse, robot_index_, call_id_, response_, {}});
    StartRead(&response_);
    return;
  }
  std::lock_guard lock(mutex_);
  release_locked();
}

void TeleopCall::OnDone(const grpc::Status& status) {
  // The last thing this object does: its owner may destroy it once the event is out.
  events_.push({BridgeEvent::Kind::TeleopEnded, robot_index_, call_id_, {}, status});
}

}  // namespace dtmf::ros_bridge
