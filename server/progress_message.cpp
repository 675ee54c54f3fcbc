// A command's progress event as the API streams it (v1::Progress): what every command RPC and
// the Teleop stream write for each of their job's events.
#include "teleop_service.h"

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

}  // namespace dtmf::server
