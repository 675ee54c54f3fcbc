#include "teleop_service.h"

#include <spdlog/spdlog.h>

#include "command/test_sequence.h"
#include "command/word_codec.h"

namespace dtmf::server {

namespace {

v1::FrameEvent frame_event(ProgressEvent::Kind kind) {
  using K = ProgressEvent::Kind;
  switch (kind) {
    case K::Queued:
      return v1::FRAME_EVENT_QUEUED;
    case K::Transmitting:
      return v1::FRAME_EVENT_TRANSMITTING;
    case K::Ack:
      return v1::FRAME_EVENT_ACK;
    case K::Nack:
      return v1::FRAME_EVENT_NACK;
    case K::NoAnswer:
      return v1::FRAME_EVENT_NO_ANSWER;
    case K::Retransmitting:
      return v1::FRAME_EVENT_RETRANSMITTING;
    case K::AwaitingDecision:
      return v1::FRAME_EVENT_AWAITING_DECISION;
    case K::Confirmed:
      return v1::FRAME_EVENT_CONFIRMED;
    case K::Continued:
      return v1::FRAME_EVENT_CONTINUED;
    case K::Failed:
      return v1::FRAME_EVENT_FAILED;
    case K::Sent:
      return v1::FRAME_EVENT_SENT;
    case K::WaitingForAir:
      return v1::FRAME_EVENT_WAITING_FOR_AIR;
  }
  return v1::FRAME_EVENT_UNSPECIFIED;
}

}  // namespace

void fill_progress(v1::Progress& out, Job& job, const ProgressEvent& event, const std::string& robot) {
  out.set_command_id(job.id());
  out.set_event(frame_event(event.kind));
  out.set_command(job.description());
  out.set_frame_index(static_cast<std::uint32_t>(event.frame_index));
  out.set_frame_count(static_cast<std::uint32_t>(event.frame_count > 0 ? event.frame_count : job.frame_count()));
  out.set_attempt(static_cast<std::uint32_t>(event.attempt));
  out.set_profile(job.profile().name);
  out.set_robot(robot);
  if (const auto& frame = event.frame) {  // none while the command waits in the queue
    if (frame->word) out.set_word(*frame->word);
    if (frame->sequence) out.set_sequence(*frame->sequence);
    out.set_frame_bits(frame->bits.bit_string(frame->bit_count));
    for (double hz : frame->tones_hz) out.add_tones_hz(hz);
    out.set_authenticated(frame->authenticated);
    out.set_synchronisation(frame->synchronisation);
    // An authenticated frame's ACK answers it only with its tag (link/answer_wait.h).
    if (event.kind == ProgressEvent::Kind::Ack || event.kind == ProgressEvent::Kind::Confirmed)
      out.set_answer_authenticated(frame->authenticated);
  }
  if (event.response_time_ms) out.set_response_time_ms(*event.response_time_ms);
  out.set_detail(event.detail);
  out.set_air_wait_reason(event.air_wait_reason);
  out.set_air_wait_left_ms(event.air_wait_left_ms);
  out.set_air_wait_ms(event.air_wait_ms);
  out.set_queue_position(static_cast<std::uint32_t>(event.queue_position));
  out.set_time_unix_ms(std::chrono::duration_cast<std::chrono::milliseconds>(event.time.time_since_epoch()).count());
}

namespace {

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

// Runs `submit`, and answers a request the transmitter refused with the status every command
// RPC gives it; nullopt when the command was accepted.
template <class Submit>
std::optional<grpc::Status> refusal_of(Submit&& submit) {
  try {
    submit();
  } catch (const RequestError& e) {
    return e.status();
  } catch (const QueueFull& e) {
    return grpc::Status{grpc::StatusCode::RESOURCE_EXHAUSTED, e.what()};
  } catch (const TransmitterUnavailable& e) {
    return grpc::Status{grpc::StatusCode::UNAVAILABLE, e.what()};
  }
  return std::nullopt;
}

// Drive, Turn, Stop and Reset each stream their own response message around one Progress.
template <typename Response>
auto progress_to(grpc::ServerWriter<Response>* writer) {
  return [writer](const v1::Progress& progress) {
    Response response;
    *response.mutable_progress() = progress;
    return writer->Write(response);
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

template <class Write>
grpc::Status TeleopService::run_command(grpc::ServerContext* context, const command::Command& command,
                                        const v1::CommandOptions& request_options, bool to_front, Write write) {
  std::shared_ptr<Job> job;
  std::string robot;
  const auto refused = refusal_of([&] {
    const CommandSettings settings = settings_of(request_options, std::holds_alternative<command::Stop>(command));
    const std::string profile = settings.profile ? settings.profile->name : transmitter_.profile().name;
    robot = transmitter_.robot_name(settings.robot);
    try {
      job = transmitter_.submit(command, settings.policy, settings.decision_timeout, to_front, settings.profile,
                                settings.robot);
    } catch (const command::ParameterError& e) {
      // The chosen profile's frames cannot carry the command (its fields, or its kind).
      throw RequestError("profile " + profile + ": " + e.what());
    } catch (const UnauthenticatedRefused& e) {
      throw RequestError(std::string("options.profile: ") + e.what());
    }
  });
  if (refused) return *refused;
  return follow(context, job, robot, write);
}

grpc::Status TeleopService::stop_every_robot(grpc::ServerContext* context, const v1::StopRequest& request,
                                             grpc::ServerWriter<v1::StopResponse>* writer) {
  std::shared_ptr<Job> job;
  std::optional<grpc::Status> refused;
  try {
    refused = refusal_of([&] {
      if (!request.options().robot().empty())
        throw RequestError("options.robot: a stop for every robot names none (leave it empty, or drop all_robots)");
      const LinkProfile* profile = command_settings(request.options(), options_.defaults).profile;
      halt_every_teleop();  // before the submit, as Stop for one robot does (the proto says why)
      try {
        job = transmitter_.submit_every_robot_stop(profile);
      } catch (const std::invalid_argument& e) {  // no profile that can send it
        throw RequestError(std::string("options.profile: ") + e.what());
      }
    });
  } catch (const RoomKeyMissing& e) {
    return {grpc::StatusCode::FAILED_PRECONDITION, std::string("all_robots: ") + e.what()};
  }
  if (refused) return *refused;
  return follow(context, job, "", progress_to(writer));
}

template <class Write>
grpc::Status TeleopService::follow(grpc::ServerContext* context, const std::shared_ptr<Job>& job,
                                   const std::string& robot, Write write) {
  bool client_gone = false;
  while (!job->finished_and_drained()) {
    if (!client_gone && context->IsCancelled()) {
      client_gone = true;  // queued frames are withdrawn; a chord on air completes
      job->cancel();
    }
    const auto event = job->next_event(std::chrono::milliseconds(100));
    if (!event || client_gone) continue;
    v1::Progress progress;
    fill_progress(progress, *job, *event, robot);
    if (!write(progress)) {
      client_gone = true;
      job->cancel();
    }
  }
  return outcome_status(*job);
}

grpc::Status TeleopService::Drive(grpc::ServerContext* context, const v1::DriveRequest* request,
                                  grpc::ServerWriter<v1::DriveResponse>* writer) {
  if (auto refused = refuse_while_teleop("Drive", request->options())) return *refused;
  try {
    return run_command(context, drive_command(*request), request->options(), false, progress_to(writer));
  } catch (const RequestError& e) {
    return e.status();
  }
}

grpc::Status TeleopService::Turn(grpc::ServerContext* context, const v1::TurnRequest* request,
                                 grpc::ServerWriter<v1::TurnResponse>* writer) {
  if (auto refused = refuse_while_teleop("Turn", request->options())) return *refused;
  try {
    return run_command(context, turn_command(*request), request->options(), false, progress_to(writer));
  } catch (const RequestError& e) {
    return e.status();
  }
}

grpc::Status TeleopService::Stop(grpc::ServerContext* context, const v1::StopRequest* request,
                                 grpc::ServerWriter<v1::StopResponse>* writer) {
  if (request->all_robots()) return stop_every_robot(context, *request, writer);
  halt_teleop(request->options());
  return run_command(context, command::Stop{}, request->options(), true, progress_to(writer));
}

grpc::Status TeleopService::Reset(grpc::ServerContext* context, const v1::ResetRequest* request,
                                  grpc::ServerWriter<v1::ResetResponse>* writer) {
  if (auto refused = refuse_while_teleop("Reset", request->options())) return *refused;
  return run_command(context, command::Reset{}, request->options(), false, progress_to(writer));
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

grpc::Status TeleopService::RunTestSequence(grpc::ServerContext* context, const v1::RunTestSequenceRequest* request,
                                            grpc::ServerWriter<v1::RunTestSequenceResponse>* writer) {
  if (auto refused = refuse_while_teleop("RunTestSequence", request->options())) return *refused;
  const LinkProfile* profile = nullptr;
  RobotIndex robot = 0;
  try {
    check_label("label", request->label());
    check_text("notes", request->notes(), kNotesLimit);
    const CommandSettings settings = settings_of(request->options());
    profile = settings.profile;
    robot = settings.robot;
  } catch (const RequestError& e) {
    return e.status();
  }
  if (!profile) profile = &transmitter_.profile();
  std::string run_id;
  if (auto started = start_run(request->label(), request->notes(), *profile, run_id); !started.ok()) return started;
  const auto commands = command::seed_test_sequence();
  // Frames per command are the link's business (a fast frame carries a whole command).
  std::uint32_t total = 0;
  for (const auto& c : commands)
    total += static_cast<std::uint32_t>(transmitter_.link_of(*profile, robot).frame_count(c));
  std::uint32_t before = 0, done = 0;  // frames of the commands already through, and in all
  grpc::Status status = grpc::Status::OK;
  for (std::size_t k = 0; k < commands.size() && status.ok(); ++k) {
    status = run_command(context, commands[k], request->options(), false, [&](const v1::Progress& p) {
      // A counter synchronisation the link put before a command is one frame more than planned.
      if (p.synchronisation() && p.event() == v1::FRAME_EVENT_TRANSMITTING) ++total;
      if (p.event() == v1::FRAME_EVENT_ACK) done = before + p.frame_index() + 1;
      if (p.event() == v1::FRAME_EVENT_CONFIRMED || p.event() == v1::FRAME_EVENT_CONTINUED)
        done = before + p.frame_count();
      v1::RunTestSequenceResponse response;
      response.set_run_id(run_id);
      response.set_command_index(static_cast<std::uint32_t>(k));
      response.set_command_count(static_cast<std::uint32_t>(commands.size()));
      response.set_frames_done(done);
      response.set_frames_total(total);
      *response.mutable_progress() = p;
      return writer->Write(response);
    });
    before = done;
  }
  end_run(run_id);
  return status;
}

}  // namespace dtmf::server
