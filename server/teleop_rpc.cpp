// TeleopService::Teleop: live driving over one bidirectional stream. This checks the first
// message and takes the slot (one stream drives at a time); teleop_stream.h drives it, and
// teleop_session.h holds its rules.
#include <spdlog/spdlog.h>

#include "command/word_codec.h"  // command::ParameterError
#include "shown_text.h"
#include "teleop_service.h"
#include "teleop_session.h"

namespace dtmf::server {

command::Velocity TeleopService::teleop_target(const v1::TeleopRequest& request, RobotIndex robot) const {
  const double lease_s = request.lease_s() == 0 ? 1.0 : request.lease_s();
  try {
    return command::velocity_command(transmitter_.model_of(robot), request.linear_mps(), request.angular_radps(),
                                     lease_s);
  } catch (const command::ParameterError& e) {
    throw RequestError(e.what());
  }
}

namespace {

// The robot `options` name, or nothing for a name no robot has.
std::optional<RobotIndex> robot_of(const Transmitter& transmitter, const v1::CommandOptions& options) {
  try {
    return transmitter.robot_named(options.robot());
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// Who a Teleop call comes from, for another's refusal: what the client calls itself
// (dtmf-console names its page) and where it called from, as gRPC saw it.
std::string driver_of(const grpc::CallbackServerContext& context) {
  const auto& metadata = context.client_metadata();
  const auto named = metadata.find("x-dtmf-client");
  const std::string peer = context.peer();
  if (named == metadata.end()) return "held by a client at " + peer;
  // The caller's own text: quoted and bounded.
  return "held by " + shown(std::string_view(named->second.data(), named->second.size())) + " at " + peer;
}

}  // namespace

std::string TeleopService::held_by(RobotIndex robot) {
  std::lock_guard lock(teleop_mutex_);
  const std::shared_ptr<TeleopSession> holder = teleop_[robot].lock();
  return holder ? ": " + holder->driver() : "";
}

std::optional<grpc::Status> TeleopService::refuse_while_teleop(const char* rpc, const v1::CommandOptions& options) {
  const auto robot = robot_of(transmitter_, options);
  if (!robot) return std::nullopt;
  std::lock_guard lock(teleop_mutex_);
  if (teleop_[*robot].expired()) return std::nullopt;
  const std::shared_ptr<TeleopSession> holder = teleop_[*robot].lock();
  return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                      std::string(rpc) + " refused: a Teleop stream drives the robot (" +
                          transmitter_.robot_name(*robot) + ")" + (holder ? ": " + holder->driver() : "") +
                          "; end that stream first, or send Stop (which overtakes and ends it)");
}

namespace {
constexpr const char* kOvertaken =
    "a Stop call overtook this Teleop stream: the robot stops; open a new stream to drive again";
}  // namespace

void TeleopService::halt_teleop(const v1::CommandOptions& options) {
  const auto robot = robot_of(transmitter_, options);
  if (!robot) return;
  std::shared_ptr<TeleopSession> active;
  {
    std::lock_guard lock(teleop_mutex_);
    active = teleop_[*robot].lock();
  }
  if (active) active->halt(kOvertaken);
}

void TeleopService::halt_every_teleop() {
  std::vector<std::shared_ptr<TeleopSession>> active;
  {
    std::lock_guard lock(teleop_mutex_);
    for (const auto& slot : teleop_) active.push_back(slot.lock());
  }
  for (const auto& session : active) {
    if (session) session->halt(kOvertaken);
  }
}

grpc::ServerBidiReactor<v1::TeleopRequest, v1::TeleopResponse>* TeleopService::Teleop(
    grpc::CallbackServerContext* context) {
  return TeleopReactor::start(transmitter_, [this, driver = driver_of(*context)](const v1::TeleopRequest& first) {
    return open_teleop(first, driver);
  });
}

std::variant<TeleopOpened, grpc::Status> TeleopService::open_teleop(const v1::TeleopRequest& first,
                                                                    const std::string& driver) {
  CommandSettings settings;
  command::Velocity target;
  try {
    settings = settings_of(first.options());
    target = teleop_target(first, settings.robot);
  } catch (const RequestError& e) {
    return e.status();
  }
  TeleopOpened opened;
  TeleopStreamSetup& setup = opened.setup;
  setup.profile = settings.profile ? settings.profile : &transmitter_.profile();
  setup.decision_timeout = settings.decision_timeout;
  setup.first_lease_s = first.lease_s();
  setup.robot = settings.robot;
  setup.target_of = [this, robot = settings.robot](const v1::TeleopRequest& request) {
    return teleop_target(request, robot);
  };
  try {
    const link::Link& link = transmitter_.link_of(*setup.profile, settings.robot);
    (void)link.frame_count(target);
    setup.carried_lease_s = std::get<command::Velocity>(link.as_received(target)).lease_s;
  } catch (const command::ParameterError& e) {
    return grpc::Status{grpc::StatusCode::INVALID_ARGUMENT, "profile " + setup.profile->name + ": " + e.what()};
  }

  opened.session = std::make_shared<TeleopSession>(transmitter_.model_of(settings.robot), driver);
  opened.slot = std::make_unique<TeleopSlot>(teleop_mutex_, teleop_[settings.robot], opened.session);
  if (!opened.slot->held()) {
    return grpc::Status{grpc::StatusCode::FAILED_PRECONDITION,
                        "another Teleop stream drives the robot (" + transmitter_.robot_name(settings.robot) + ")" +
                            held_by(settings.robot) + "; one stream drives a robot at a time (end it, or send Stop)"};
  }
  setup.first_target = target;
  spdlog::info("teleop stream opened (robot {}, {}, lease {:.2f} s)", transmitter_.robot_name(settings.robot),
               setup.profile->name, target.lease_s);
  return opened;
}

}  // namespace dtmf::server
