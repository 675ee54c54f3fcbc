// TeleopService::Teleop: live driving over one bidirectional stream (teleop_session.h holds
// its rules). A reader thread takes the client's targets; this thread sends the newest one
// frame at a time through the transmitter (Policy::Live: once, no retransmission) and
// answers with the status after each frame's event. The slot: one stream drives at a time.
#include <spdlog/spdlog.h>

#include <atomic>
#include <thread>

#include "command/word_codec.h"
#include "teleop_service.h"
#include "teleop_session.h"

namespace dtmf::server {

namespace {

double steady_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// How long the reader may take to notice the end of a stream the server ends: the client
// repeats its target at least once a second, and each message read lets the reader see it.
// A client silent this long holds the slot no more (its lease lapsed long ago).
constexpr double kClientGone_s = 10.0;
constexpr auto kReaderGrace = std::chrono::milliseconds(1500);

}  // namespace

command::Velocity TeleopService::teleop_target(const v1::TeleopRequest& request) const {
  const double lease_s = request.lease_s() == 0 ? 1.0 : request.lease_s();
  try {
    return command::velocity_command(options_.robot, request.linear_mps(), request.angular_radps(), lease_s);
  } catch (const command::ParameterError& e) {
    throw RequestError(e.what());
  }
}

bool TeleopService::claim_teleop(const std::shared_ptr<TeleopSession>& session) {
  std::lock_guard lock(teleop_mutex_);
  if (auto active = teleop_.lock()) return false;
  teleop_ = session;
  return true;
}

std::optional<grpc::Status> TeleopService::refuse_while_teleop(const char* rpc) {
  std::lock_guard lock(teleop_mutex_);
  if (teleop_.expired()) return std::nullopt;
  return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                      std::string(rpc) +
                          " refused: a Teleop stream drives the robot; end that stream first, or send "
                          "Stop (which overtakes and ends it)");
}

void TeleopService::halt_teleop() {
  std::shared_ptr<TeleopSession> active;
  {
    std::lock_guard lock(teleop_mutex_);
    active = teleop_.lock();
  }
  if (active)
    active->halt("a Stop call overtook this Teleop stream: the robot stops; open a new stream to drive again");
}

grpc::Status TeleopService::Teleop(grpc::ServerContext* context,
                                   grpc::ServerReaderWriter<v1::TeleopResponse, v1::TeleopRequest>* stream) {
  v1::TeleopRequest first;
  if (!stream->Read(&first)) return grpc::Status::OK;  // closed before it asked for anything
  CommandSettings settings;
  command::Velocity target;
  try {
    settings = settings_of(first.options());
    target = teleop_target(first);
  } catch (const RequestError& e) {
    return e.status();
  }
  const LinkProfile& profile = settings.profile ? *settings.profile : transmitter_.profile();
  double carried_lease_s = 0;  // the lease as the frames carry it
  try {
    const link::Link& link = transmitter_.link_of(profile);
    (void)link.frame_count(target);
    carried_lease_s = std::get<command::Velocity>(link.as_received(target)).lease_s;
  } catch (const command::ParameterError& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "profile " + profile.name + ": " + e.what()};
  }

  auto session = std::make_shared<TeleopSession>(options_.robot);
  if (!claim_teleop(session)) {
    return {grpc::StatusCode::FAILED_PRECONDITION,
            "another Teleop stream drives the robot; one stream drives at a time (end it, or send Stop)"};
  }
  session->set_target(target, steady_s());
  spdlog::info("teleop stream opened ({}, lease {:.2f} s)", profile.name, target.lease_s);

  std::optional<grpc::Status> refused;  // a bad target mid-stream, set by the reader only
  std::atomic<bool> reader_done{false};
  std::thread reader([&] {
    v1::TeleopRequest request;
    while (!session->stream_ended() && !session->halted() && stream->Read(&request)) {
      request.set_lease_s(first.lease_s());  // the stream's lease is the first message's
      try {
        session->set_target(teleop_target(request), steady_s());
      } catch (const RequestError& e) {
        refused = e.status();
        break;
      }
    }
    session->end_stream();
    reader_done = true;
  });

  grpc::Status status = grpc::Status::OK;
  auto write_status = [&](const v1::Progress* progress) {
    const TeleopStatus s = session->status(steady_s());
    v1::TeleopResponse response;
    if (progress) *response.mutable_progress() = *progress;
    response.set_target_linear_mps(s.target_linear_mps);
    response.set_target_angular_radps(s.target_angular_radps);
    response.set_confirmed(s.confirmed.has_value());
    if (s.confirmed) {
      response.set_confirmed_linear_mps(s.confirmed->linear_mps);
      response.set_confirmed_angular_radps(s.confirmed->angular_radps);
    }
    response.set_response_time_ms(s.response_time_ms);
    response.set_link_quality(s.link_quality);
    response.set_frames_in_window(static_cast<std::uint32_t>(s.frames_in_window));
    response.set_link_window_s(kLinkWindow_s);
    response.set_lease_s(carried_lease_s);
    response.set_lease_left_s(s.lease_left_s);
    return stream->Write(response);
  };

  while (true) {
    if (context->IsCancelled()) {
      status = {grpc::StatusCode::CANCELLED, "the client cancelled the Teleop stream"};
      break;
    }
    if (auto why = session->halted()) {
      status = {grpc::StatusCode::ABORTED, *why};
      break;
    }
    if (session->stream_ended()) {
      if (refused) status = *refused;
      break;
    }
    if (session->silent_s(steady_s()) > kClientGone_s) {
      status = {grpc::StatusCode::DEADLINE_EXCEEDED,
                "the client sent nothing for " + std::to_string(static_cast<int>(kClientGone_s)) +
                    " s: the stream is closed (the robot stopped when its lease ended)"};
      break;
    }
    const auto due = session->frame_due(steady_s());
    if (!due) {
      session->wait(0.05);
      continue;
    }
    std::shared_ptr<Job> job;
    try {
      job = transmitter_.submit(*due, Policy::Live, settings.decision_timeout, false, &profile);
    } catch (const QueueFull& e) {
      status = {grpc::StatusCode::RESOURCE_EXHAUSTED, e.what()};
      break;
    } catch (const TransmitterUnavailable& e) {
      status = {grpc::StatusCode::UNAVAILABLE, e.what()};
      break;
    }
    bool answered = false, confirmed = false, client_gone = false;
    double response_ms = 0;
    while (!job->finished_and_drained()) {
      if (!client_gone && (context->IsCancelled() || session->halted())) {
        client_gone = true;  // a chord on air completes; nothing more is sent for this stream
        job->cancel();
      }
      const auto event = job->next_event(std::chrono::milliseconds(50));
      if (!event) continue;
      if (event->kind == ProgressEvent::Kind::Ack || event->kind == ProgressEvent::Kind::Nack) answered = true;
      if (event->kind == ProgressEvent::Kind::Ack) {
        confirmed = true;
        response_ms = event->response_time_ms.value_or(0);
      }
      if (event->kind == ProgressEvent::Kind::Confirmed || event->kind == ProgressEvent::Kind::Continued ||
          event->kind == ProgressEvent::Kind::Failed) {
        const auto executed = std::get<command::Velocity>(job->link().as_received(job->command()));
        session->frame_ended(steady_s(), answered, confirmed ? std::optional(executed) : std::nullopt, response_ms);
      }
      if (client_gone) continue;
      v1::Progress progress;
      fill_progress(progress, *job, *event);
      if (!write_status(&progress)) {
        client_gone = true;
        job->cancel();
      }
    }
    if (job->outcome() == Outcome::Unavailable) {
      status = {grpc::StatusCode::UNAVAILABLE, job->outcome_detail()};
      break;
    }
  }
  if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
    v1::Progress last;
    last.set_event(v1::FRAME_EVENT_FAILED);
    last.set_detail(status.error_message());
    last.set_profile(profile.name);
    write_status(&last);
  }
  // The reader stops at the client's next message or the stream's end; a client silent for
  // longer than that has gone, and cancelling the call ends its Read.
  session->end_stream();
  const auto deadline = std::chrono::steady_clock::now() + kReaderGrace;
  while (!reader_done && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!reader_done) context->TryCancel();
  reader.join();
  {
    std::lock_guard lock(teleop_mutex_);
    teleop_.reset();
  }
  spdlog::info("teleop stream closed: {}", status.ok() ? "the client ended it" : status.error_message());
  return status;
}

}  // namespace dtmf::server
