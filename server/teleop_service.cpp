// TeleopService's command RPCs (Drive, Turn, Stop, Reset, RunTestSequence, Decide): each checks
// its request, submits through the transmitter, and follows its job with a CommandReactor; a
// refusal of the sender's becomes one status per kind (status_of).
#include "teleop_service.h"

#include "command/test_sequence.h"
#include "command_reactor.h"

namespace dtmf::server {

grpc::Status outcome_status(Job& job) {
  const std::string detail = job.outcome_detail();
  switch (job.outcome()) {
    case Outcome::Confirmed:
    case Outcome::Continued:
    case Outcome::Sent:
      return grpc::Status::OK;
    case Outcome::Cancelled:
      return {grpc::StatusCode::CANCELLED, detail};
    case Outcome::Unavailable:
      return {grpc::StatusCode::UNAVAILABLE, detail};
    default:
      return {grpc::StatusCode::ABORTED, job.description() + ": " + detail};
  }
}

grpc::Status status_of(const Refusal& refusal) {
  using K = Refusal::Kind;
  switch (refusal.kind) {
    case K::QueueFull:
      return {grpc::StatusCode::RESOURCE_EXHAUSTED, refusal.why};
    case K::Unavailable:
      return {grpc::StatusCode::UNAVAILABLE, refusal.why};
    case K::Unrecorded:
      return {grpc::StatusCode::INTERNAL, refusal.why};
    case K::RoomKeyMissing:
      return {grpc::StatusCode::FAILED_PRECONDITION, "all_robots: " + refusal.why};
    case K::Unauthenticated:
    case K::NoProfile:
      return {grpc::StatusCode::INVALID_ARGUMENT, "options.profile: " + refusal.why};
    case K::Unsendable:
      return {grpc::StatusCode::INVALID_ARGUMENT, refusal.why};
  }
  return {grpc::StatusCode::INTERNAL, refusal.why};
}

namespace {

// What a command RPC follows: its job, or the status that ends it at once.
using Followed = std::variant<std::shared_ptr<Job>, grpc::Status>;

// Runs `submit`: the job, or the status of its refusal, or of a request found bad before it.
template <class Submit>
Followed followed(Submit&& submit) {
  try {
    Submitted submitted = submit();
    if (auto* job = std::get_if<std::shared_ptr<Job>>(&submitted)) return std::move(*job);
    return status_of(std::get<Refusal>(submitted));
  } catch (const RequestError& e) {
    return e.status();
  }
}

// Follows one job: it, and the end once it ended well.
CommandReactor<v1::StopResponse>::Next one_job(Followed submitted) {
  return [submitted = std::move(submitted)](const Job* last) -> Followed {
    if (last) return grpc::Status::OK;
    return submitted;
  };
}

// Drive, Turn, Stop and Reset each stream their own response message around one Progress.
template <class Response>
typename CommandReactor<Response>::Fill progress_of(std::string robot) {
  return [robot = std::move(robot)](Response& response, Job& job, const ProgressEvent& event) {
    fill_progress(*response.mutable_progress(), job, event, robot);
  };
}

}  // namespace

TeleopService::TeleopService(Transmitter& transmitter, store::Store& store, ServiceOptions options)
    : transmitter_(transmitter), store_(store), options_(std::move(options)), teleop_(transmitter.robots().size()) {}

CommandSettings TeleopService::settings_of(const v1::CommandOptions& options, bool stop) const {
  CommandSettings settings = command_settings(options, options_.defaults);
  try {
    settings.robot = transmitter_.robot_named(options.robot());
  } catch (const std::invalid_argument& e) {
    throw RequestError(std::string("options.robot: ") + e.what());
  }
  try {
    settings.profile = &transmitter_.sendable_profile(settings.profile, stop, settings.robot);
  } catch (const std::invalid_argument& e) {
    throw RequestError(std::string("options.profile: ") + e.what());
  }
  return settings;
}

std::variant<std::shared_ptr<Job>, grpc::Status> TeleopService::submit(const command::Command& command,
                                                                       const v1::CommandOptions& request_options,
                                                                       bool to_front) {
  return followed([&] {
    const CommandSettings settings = settings_of(request_options, std::holds_alternative<command::Stop>(command));
    return transmitter_.submit(command, settings.policy, settings.decision_timeout, to_front, settings.profile,
                               settings.robot);
  });
}

template <class Response>
grpc::ServerWriteReactor<Response>* TeleopService::run_command(const command::Command& command,
                                                               const v1::CommandOptions& options, bool to_front) {
  Followed submitted = submit(command, options, to_front);
  std::string robot;
  if (auto* job = std::get_if<std::shared_ptr<Job>>(&submitted)) robot = (*job)->robot();
  return CommandReactor<Response>::start(one_job(std::move(submitted)), progress_of<Response>(std::move(robot)));
}

grpc::ServerWriteReactor<v1::StopResponse>* TeleopService::stop_every_robot(const v1::StopRequest& request) {
  Followed submitted = followed([&] {
    if (!request.options().robot().empty())
      throw RequestError("options.robot: a stop for every robot names none (leave it empty, or drop all_robots)");
    const LinkProfile* profile = command_settings(request.options(), options_.defaults).profile;
    halt_every_teleop();  // before the submit, as Stop for one robot does (the proto says why)
    return transmitter_.submit_every_robot_stop(profile);
  });
  return CommandReactor<v1::StopResponse>::start(one_job(std::move(submitted)), progress_of<v1::StopResponse>(""));
}

namespace {
// A command refused before it was queued: its status, and done.
template <class Response>
grpc::ServerWriteReactor<Response>* refused(const grpc::Status& status) {
  return CommandReactor<Response>::start([status](const Job*) -> Followed { return status; },
                                         [](Response&, Job&, const ProgressEvent&) {});
}
}  // namespace

grpc::ServerWriteReactor<v1::DriveResponse>* TeleopService::Drive(grpc::CallbackServerContext*,
                                                                  const v1::DriveRequest* request) {
  if (auto refusal = refuse_while_teleop("Drive", request->options())) return refused<v1::DriveResponse>(*refusal);
  try {
    return run_command<v1::DriveResponse>(drive_command(*request), request->options(), false);
  } catch (const RequestError& e) {
    return refused<v1::DriveResponse>(e.status());
  }
}

grpc::ServerWriteReactor<v1::TurnResponse>* TeleopService::Turn(grpc::CallbackServerContext*,
                                                                const v1::TurnRequest* request) {
  if (auto refusal = refuse_while_teleop("Turn", request->options())) return refused<v1::TurnResponse>(*refusal);
  try {
    return run_command<v1::TurnResponse>(turn_command(*request), request->options(), false);
  } catch (const RequestError& e) {
    return refused<v1::TurnResponse>(e.status());
  }
}

grpc::ServerWriteReactor<v1::StopResponse>* TeleopService::Stop(grpc::CallbackServerContext*,
                                                                const v1::StopRequest* request) {
  if (request->all_robots()) return stop_every_robot(*request);
  halt_teleop(request->options());
  return run_command<v1::StopResponse>(command::Stop{}, request->options(), true);
}

grpc::ServerWriteReactor<v1::ResetResponse>* TeleopService::Reset(grpc::CallbackServerContext*,
                                                                  const v1::ResetRequest* request) {
  if (auto refusal = refuse_while_teleop("Reset", request->options())) return refused<v1::ResetResponse>(*refusal);
  return run_command<v1::ResetResponse>(command::Reset{}, request->options(), false);
}

grpc::Status TeleopService::Decide(grpc::ServerContext*, const v1::DecideRequest* request, v1::DecideResponse*) {
  try {
    if (!transmitter_.decide(request->command_id(), decision_of(*request))) {
      return {grpc::StatusCode::FAILED_PRECONDITION,
              "command " + request->command_id() + " is not awaiting a decision (it may have ended or timed out)"};
    }
    return grpc::Status::OK;
  } catch (const RequestError& e) {
    return e.status();
  }
}

namespace {
// The seed's test sequence as it goes: which command, and frames done of all.
struct SequenceProgress {
  std::string run_id;
  std::vector<command::Command> commands = command::seed_test_sequence();
  std::size_t index = 0;
  std::uint32_t before = 0, done = 0, total = 0;  // frames of the commands already through, and in all
};
}  // namespace

grpc::ServerWriteReactor<v1::RunTestSequenceResponse>* TeleopService::RunTestSequence(
    grpc::CallbackServerContext*, const v1::RunTestSequenceRequest* request) {
  using Reactor = CommandReactor<v1::RunTestSequenceResponse>;
  if (auto refusal = refuse_while_teleop("RunTestSequence", request->options()))
    return refused<v1::RunTestSequenceResponse>(*refusal);
  const LinkProfile* profile = nullptr;
  RobotIndex robot = 0;
  try {
    check_label("label", request->label());
    check_text("notes", request->notes(), kNotesLimit);
    const CommandSettings settings = settings_of(request->options());
    profile = settings.profile;
    robot = settings.robot;
  } catch (const RequestError& e) {
    return refused<v1::RunTestSequenceResponse>(e.status());
  }
  if (!profile) profile = &transmitter_.profile();
  auto run = std::make_shared<SequenceProgress>();
  if (auto started = start_run(request->label(), request->notes(), *profile, run->run_id); !started.ok())
    return refused<v1::RunTestSequenceResponse>(started);
  // Frames per command are the link's business (a fast frame carries a whole command).
  for (const auto& c : run->commands)
    run->total += static_cast<std::uint32_t>(transmitter_.link_of(*profile, robot).frame_count(c));
  Reactor::Next next = [this, run, options = request->options()](const Job* last) -> Followed {
    if (last) {
      run->before = run->done;
      ++run->index;
    }
    if (run->index == run->commands.size()) return grpc::Status::OK;
    return submit(run->commands[run->index], options, false);
  };
  Reactor::Fill fill = [run](v1::RunTestSequenceResponse& response, Job& job, const ProgressEvent& event) {
    v1::Progress& p = *response.mutable_progress();
    fill_progress(p, job, event, job.robot());
    // A counter synchronisation the link put before a command is one frame more than planned.
    if (p.synchronisation() && p.event() == v1::FRAME_EVENT_TRANSMITTING) ++run->total;
    if (p.event() == v1::FRAME_EVENT_ACK) run->done = run->before + p.frame_index() + 1;
    if (p.event() == v1::FRAME_EVENT_CONFIRMED || p.event() == v1::FRAME_EVENT_CONTINUED)
      run->done = run->before + p.frame_count();
    response.set_run_id(run->run_id);
    response.set_command_index(static_cast<std::uint32_t>(run->index));
    response.set_command_count(static_cast<std::uint32_t>(run->commands.size()));
    response.set_frames_done(run->done);
    response.set_frames_total(run->total);
  };
  return Reactor::start(std::move(next), std::move(fill), [this, run] { end_run(run->run_id); });
}

}  // namespace dtmf::server
