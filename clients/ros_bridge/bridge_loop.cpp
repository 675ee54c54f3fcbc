#include "bridge_loop.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

namespace dtmf::ros_bridge {
namespace {

std::vector<std::string> names_of(const std::vector<BridgeRobot>& robots) {
  std::vector<std::string> names;
  for (const BridgeRobot& r : robots) names.push_back(r.name);
  return names;
}

StreamEnd end_of(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
    case grpc::StatusCode::CANCELLED:
      return StreamEnd::Finished;
    case grpc::StatusCode::ABORTED:
      return StreamEnd::Stopped;
    default:
      return StreamEnd::Failed;
  }
}

LinkReading reading_of(const v1::TeleopResponse& r) {
  LinkReading reading;
  const v1::FrameEvent event = r.progress().event();
  reading.answered = event == v1::FRAME_EVENT_ACK || event == v1::FRAME_EVENT_NACK;
  reading.unanswered = event == v1::FRAME_EVENT_NO_ANSWER;
  reading.link_quality = r.link_quality();
  reading.frames_in_window = r.frames_in_window();
  reading.window_s = r.link_window_s();
  reading.response_time_ms = r.response_time_ms();
  reading.lease_s = r.lease_s();
  reading.lease_left_s = r.lease_left_s();
  if (r.confirmed()) reading.confirmed = Twist{r.confirmed_linear_mps(), r.confirmed_angular_radps()};
  return reading;
}

}  // namespace

BridgeLoop::BridgeLoop(std::shared_ptr<grpc::Channel> channel, BridgeSettings settings)
    : stub_(v1::TeleopService::NewStub(std::move(channel))),
      settings_(std::move(settings)),
      topics_(bridge_topics(names_of(settings_.robots))),
      inputs_(settings_.domain, topics_),
      outputs_(inputs_.participant(), topics_),
      events_([this] { inputs_.wake(); }) {
  for (const BridgeRobot& r : settings_.robots) {
    robots_.push_back({r.name, TwistInput(r.limits, settings_.timeout_ms), TeleopPlan(settings_.lease_s * 1000.0),
                       LinkHealth(), nullptr, 0, std::nullopt, ""});
  }
}

BridgeLoop::~BridgeLoop() {
  // A call may not be destroyed before gRPC is done with it (its OnDone): cancel, then wait.
  for (Robot& r : robots_) {
    if (r.call) r.call->cancel();
  }
  if (stop_call_) stop_call_->cancel();
  auto calls_left = [this] {
    return stop_call_ != nullptr ||
           std::any_of(robots_.begin(), robots_.end(), [](const Robot& r) { return r.call != nullptr; });
  };
  while (calls_left()) {
    inputs_.wait(100);
    for (const BridgeEvent& e : events_.take()) {
      if (e.kind == BridgeEvent::Kind::StopEnded) stop_call_.reset();
      if (e.kind == BridgeEvent::Kind::TeleopEnded && robots_[e.robot].call_id == e.call) robots_[e.robot].call.reset();
    }
  }
}

double BridgeLoop::now_ms() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void BridgeLoop::stop() {
  leaving_ = true;
  inputs_.wake();
}

void BridgeLoop::take_inputs(double now_ms) {
  for (const DdsInputs::Heard& heard : inputs_.take_twists()) {
    Robot& robot = robots_[heard.robot];
    const TakeResult result = robot.input.take(heard.twist, now_ms);
    if (!result.first_of_its_kind) continue;
    const std::string& topic = topics_.robots[heard.robot].cmd_vel;
    if (result.verdict == TwistVerdict::Clamped) {
      spdlog::warn("{}: linear.x {} m/s, angular.z {} rad/s is beyond {}'s limits: clamped to them (said once)", topic,
                   heard.twist.linear_mps, heard.twist.angular_radps, robot.name);
    } else if (result.verdict == TwistVerdict::NotFinite) {
      spdlog::warn("{}: a message with a NaN or infinite velocity was dropped; the last good one holds (said once)",
                   topic);
    }
  }
  if (inputs_.take_stop_every_robot() && !stop_call_) {
    spdlog::warn("{}: stopping every robot in the room", topics_.stop_every_robot);
    stop_call_ = std::make_unique<StopCall>(*stub_, settings_.profile, settings_.token, events_);
  }
}

void BridgeLoop::handle_stream_end(Robot& robot, const grpc::Status& status, double now_ms) {
  const StreamEnd end = end_of(status);
  robot.plan.on_stream_end(end, now_ms);
  robot.call.reset();
  if (end == StreamEnd::Stopped) {
    spdlog::warn("{}: a stop ended the stream; the robot drives again once its cmd_vel is zero or silent", robot.name);
  } else if (end == StreamEnd::Failed) {
    const std::string what = status.error_message().substr(0, 200);
    if (what != robot.last_failure) {
      spdlog::error("{}: Teleop failed: \"{}\"; trying again every {} s while cmd_vel asks to move", robot.name, what,
                    TeleopPlan::kRetryMs / 1000);
    }
    robot.last_failure = what;
    return;
  }
  robot.last_failure.clear();
}

void BridgeLoop::handle(const BridgeEvent& event, double now_ms) {
  if (event.kind == BridgeEvent::Kind::StopEnded) {
    if (!event.status.ok())
      spdlog::error("the stop for every robot: \"{}\"", event.status.error_message().substr(0, 200));
    stop_call_.reset();
    return;
  }
  Robot& robot = robots_[event.robot];
  if (event.call != robot.call_id) return;  // from a stream already ended
  if (event.kind == BridgeEvent::Kind::TeleopEnded) {
    handle_stream_end(robot, event.status, now_ms);
    return;
  }
  const LinkReading reading = reading_of(event.response);
  robot.health.on_reading(reading, now_ms);
  if (reading.confirmed && reading.confirmed != robot.confirmed) {
    robot.confirmed = reading.confirmed;
    robot.plan.on_confirmed(*reading.confirmed);
    outputs_.publish_confirmed(event.robot, *reading.confirmed, std::chrono::system_clock::now());
  }
}

void BridgeLoop::drive(std::size_t index, double now_ms) {
  Robot& robot = robots_[index];
  const Twist wanted = leaving_ ? Twist{} : robot.input.wanted(now_ms);
  // Held -> Closed -> Open takes two steps; no state loops back to itself with a call.
  for (int i = 0; i < 2; ++i) {
    const std::optional<PlanCall> call = robot.plan.step(wanted, now_ms);
    if (!call) continue;
    if (call->kind == PlanCall::Kind::Open) {
      robot.call_id = next_call_id_++;
      robot.confirmed.reset();
      const TeleopCallOptions options{robot.name, settings_.profile, settings_.lease_s, settings_.token};
      robot.call = std::make_unique<TeleopCall>(*stub_, options, call->target, events_, index, robot.call_id);
    } else if (call->kind == PlanCall::Kind::Write) {
      robot.call->write(call->target);
    } else {
      robot.call->close();
    }
    return;
  }
}

void BridgeLoop::publish_diagnostics(double now_ms) {
  std::vector<RobotHealth> health;
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    const Robot& r = robots_[i];
    health.push_back({r.name, r.health.report(r.plan.state(), now_ms)});
    health.back().report.values.push_back({"cmd_vel messages taken", std::to_string(r.input.taken())});
    // The robot's own output heard on its topic and not sent back (dds_inputs.h).
    health.back().report.values.push_back(
        {"robot's own cmd_vel skipped", std::to_string(inputs_.skipped_from_agent(i))});
  }
  outputs_.publish_diagnostics(health, std::chrono::system_clock::now());
}

bool BridgeLoop::everything_stopped() const {
  return !stop_call_ && std::all_of(robots_.begin(), robots_.end(), [](const Robot& r) { return r.call == nullptr; });
}

double BridgeLoop::next_wake_ms(double now_ms, double leave_at_ms) const {
  double at = std::min(next_diagnostics_ms_, leave_at_ms);
  for (const Robot& r : robots_) {
    if (const auto expiry = r.input.expires_ms(now_ms)) at = std::min(at, *expiry);
    if (const auto deadline = r.plan.next_deadline_ms()) at = std::min(at, *deadline);
  }
  return at;
}

void BridgeLoop::run() {
  double leave_at_ms = 1e300;
  next_diagnostics_ms_ = now_ms();
  for (;;) {
    const double now = now_ms();
    take_inputs(now);
    for (const BridgeEvent& event : events_.take()) handle(event, now);
    if (leaving_ && leave_at_ms > now + kLeaveMs) leave_at_ms = now + kLeaveMs;
    for (std::size_t i = 0; i < robots_.size(); ++i) drive(i, now);
    if (now >= next_diagnostics_ms_) {
      publish_diagnostics(now);
      next_diagnostics_ms_ = now + settings_.diagnostics_period_ms;
    }
    if (leaving_ && (everything_stopped() || now >= leave_at_ms)) break;
    inputs_.wait(next_wake_ms(now, leave_at_ms) - now);
  }
  publish_diagnostics(now_ms());
}

}  // namespace dtmf::ros_bridge
