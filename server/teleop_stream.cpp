#include "teleop_stream.h"

#include <spdlog/spdlog.h>

#include "request_validation.h"
#include "teleop_service.h"

namespace dtmf::server {

namespace {

double steady_s(std::chrono::steady_clock::time_point at = std::chrono::steady_clock::now()) {
  return std::chrono::duration<double>(at.time_since_epoch()).count();
}

// A lease is renewed more than twice a second, and twice within it: a lost renewal costs none.
// A renewal due may wait 100 ms for the queue and a frame on air (215 ms at most) before it
// starts: 715 ms at worst, before the session's own renewal (kJointRenewalLate) takes over.
double renewal_every_ms(double lease_s) { return std::min(400.0, 400.0 * lease_s); }

// A client silent this long holds the slot no more (its lease lapsed long ago).
constexpr double kClientGone_s = 10.0;
// How long the reader may take to notice the end of a stream the server ends: the client
// repeats its target at least once a second, and each message read lets the reader see it.
constexpr auto kReaderGrace = std::chrono::milliseconds(1500);
// How long the sender waits for a new target or a frame's next event before it looks at the
// stream again (a cancelled call, a Stop): the session and the job wake it sooner.
constexpr auto kLook = std::chrono::milliseconds(50);
constexpr double kLook_s = std::chrono::duration<double>(kLook).count();

}  // namespace

TeleopSlot::TeleopSlot(std::mutex& mutex, std::weak_ptr<TeleopSession>& holder,
                       const std::shared_ptr<TeleopSession>& session)
    : mutex_(mutex), holder_(holder) {
  std::lock_guard lock(mutex_);
  if (!holder_.expired()) return;
  holder_ = session;
  held_ = true;
}

TeleopSlot::~TeleopSlot() {
  if (!held_) return;
  std::lock_guard lock(mutex_);
  holder_.reset();
}

TeleopStream::TeleopStream(grpc::ServerContext& context, Stream& stream, std::shared_ptr<TeleopSession> session,
                           Transmitter& transmitter, TeleopStreamSetup setup)
    : context_(context),
      stream_(stream),
      session_(std::move(session)),
      transmitter_(transmitter),
      setup_(std::move(setup)) {
  session_->set_target(setup_.first_target, steady_s());
  reader_ = std::thread([this] { read_targets(); });
}

TeleopStream::~TeleopStream() {
  if (renewing_) transmitter_.stop_renewing(setup_.robot);
  if (job_) job_->cancel();  // a chord on air completes; nothing more is sent for this stream
  // The reader stops at the client's next message or the stream's end; a client silent for
  // longer than that has gone, and cancelling the call ends its Read.
  session_->end_stream();
  if (reader_finished_.wait_for(kReaderGrace) != std::future_status::ready) context_.TryCancel();
  reader_.join();
}

void TeleopStream::read_targets() {
  try {
    v1::TeleopRequest request;
    while (!session_->stream_ended() && !session_->halted() && stream_.Read(&request)) {
      request.set_lease_s(setup_.first_lease_s);  // the stream's lease is the first message's
      try {
        session_->set_target(setup_.target_of(request), steady_s());
      } catch (const RequestError& e) {
        std::lock_guard lock(refused_mutex_);
        refused_ = e.status();
        break;
      }
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(refused_mutex_);
    refused_ = grpc::Status(grpc::StatusCode::INTERNAL, std::string("reading the Teleop stream failed: ") + e.what());
  }
  session_->end_stream();
  reader_done_.set_value();
}

grpc::Status TeleopStream::drive() {
  grpc::Status status;
  try {
    status = drive_frames();
  } catch (const QueueFull& e) {
    status = {grpc::StatusCode::RESOURCE_EXHAUSTED, e.what()};
  } catch (const TransmitterUnavailable& e) {
    status = {grpc::StatusCode::UNAVAILABLE, e.what()};
  } catch (const std::invalid_argument& e) {  // UnauthenticatedRefused, command::ParameterError
    status = {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  } catch (const std::exception& e) {
    status = {grpc::StatusCode::INTERNAL, std::string("the Teleop stream failed: ") + e.what() +
                                              "; the robot stops when its lease ends, and a new stream may drive it"};
  }
  if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) write_failure(status);
  return status;
}

grpc::Status TeleopStream::drive_frames() {
  while (true) {
    if (context_.IsCancelled()) return {grpc::StatusCode::CANCELLED, "the client cancelled the Teleop stream"};
    if (auto why = session_->halted()) return {grpc::StatusCode::ABORTED, *why};
    if (session_->stream_ended()) {
      std::lock_guard lock(refused_mutex_);
      return refused_.value_or(grpc::Status::OK);
    }
    if (session_->silent_s(steady_s()) > kClientGone_s) {
      return {grpc::StatusCode::DEADLINE_EXCEEDED,
              "the client sent nothing for " + std::to_string(static_cast<int>(kClientGone_s)) +
                  " s: the stream is closed (the robot stopped when its lease ended)"};
    }
    follow_renewals();
    const auto due = session_->frame_due(steady_s(), renewing_);
    if (!due) {
      session_->wait(kLook_s);
      continue;
    }
    if (auto ended = send_frame(*due)) return *ended;
  }
}

void TeleopStream::follow_renewals() {
  const bool renewable = session_->renewable(steady_s());
  if (renewable && !renewing_) {
    renewing_ = transmitter_.keep_renewed(setup_.robot, *setup_.profile, renewal_every_ms(setup_.carried_lease_s),
                                          1000 * setup_.carried_lease_s);
  } else if (!renewable && renewing_) {
    transmitter_.stop_renewing(setup_.robot);
    renewing_ = false;
  }
  if (renewing_) {
    if (const auto at = transmitter_.last_renewed(setup_.robot)) session_->renewed(steady_s(*at));
  }
}

std::optional<grpc::Status> TeleopStream::send_frame(const command::Velocity& velocity) {
  job_ = transmitter_.submit(velocity, Policy::Live, setup_.decision_timeout, false, setup_.profile, setup_.robot);
  bool answered = false, confirmed = false, client_gone = false;
  double response_ms = 0;
  while (!job_->finished_and_drained()) {
    if (!client_gone && (context_.IsCancelled() || session_->halted())) {
      client_gone = true;  // a chord on air completes; nothing more is sent for this stream
      job_->cancel();
    }
    const auto event = job_->next_event(kLook);
    if (!event) continue;
    using Kind = ProgressEvent::Kind;
    if (event->kind == Kind::Ack || event->kind == Kind::Nack) answered = true;
    if (event->kind == Kind::Ack) {
      confirmed = true;
      response_ms = event->response_time_ms.value_or(0);
    }
    if (event->kind == Kind::Confirmed || event->kind == Kind::Continued || event->kind == Kind::Failed) {
      const auto executed = std::get<command::Velocity>(job_->link().as_received(job_->command()));
      session_->frame_ended(steady_s(), answered, confirmed ? std::optional(executed) : std::nullopt, response_ms);
    }
    if (client_gone) continue;
    v1::Progress progress;
    fill_progress(progress, *job_, *event, transmitter_.robot_name(setup_.robot));
    if (!write_status(&progress)) {
      client_gone = true;
      job_->cancel();
    }
  }
  const std::shared_ptr<Job> job = std::exchange(job_, nullptr);
  if (job->outcome() == Outcome::Unavailable) return grpc::Status(grpc::StatusCode::UNAVAILABLE, job->outcome_detail());
  return std::nullopt;
}

bool TeleopStream::write_status(const v1::Progress* progress) {
  const TeleopStatus s = session_->status(steady_s());
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
  response.set_lease_s(setup_.carried_lease_s);
  response.set_lease_left_s(s.lease_left_s);
  return stream_.Write(response);
}

void TeleopStream::write_failure(const grpc::Status& status) {
  v1::Progress last;
  last.set_event(v1::FRAME_EVENT_FAILED);
  last.set_detail(status.error_message());
  last.set_profile(setup_.profile->name);
  try {
    write_status(&last);
  } catch (const std::exception& e) {
    spdlog::warn("teleop stream: the last status was not written: {}", e.what());
  }
}

}  // namespace dtmf::server
