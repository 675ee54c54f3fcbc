// Transmitter: what it publishes to the air's fan-out (air_fanout.h), for WatchAir. A
// command's progress events become frames played, answers taken and commands ended; the
// microphone's reader adds every answer heard, the air heard busy or quiet, and spectrum
// columns while someone watches them. Publishing never waits for a watcher.
#include <spdlog/spdlog.h>

#include "transmitter.h"

namespace dtmf::server {

namespace {

using Kind = ProgressEvent::Kind;

std::string frame_kind(const Job& job, const link::TransmitFrame& frame) {
  if (job.renewal()) return "renewal";
  if (frame.broadcast) return "stop_every_robot";
  return frame.synchronisation ? "synchronisation" : "command";
}

FramePlayed frame_played(const Job& job, const ProgressEvent& event) {
  const link::TransmitFrame& frame = *event.frame;
  FramePlayed played{job.id(),
                     job.description(),
                     {},
                     frame_kind(job, frame),
                     job.profile().name,
                     frame.sequence ? std::optional<unsigned>(*frame.sequence) : std::nullopt,
                     frame.counter,
                     frame.authenticated,
                     event.frame_index,
                     event.frame_count,
                     event.attempt,
                     frame.tone_ms,
                     event.air_wait_ms};
  if (job.renewal()) {
    for (const Job::Renewed& r : job.renewed()) played.robots.push_back(r.robot);
  } else if (!job.robot().empty()) {
    played.robots.push_back(job.robot());
  }
  return played;
}

FrameAnswered frame_answered(const Job& job, const ProgressEvent& event) {
  const bool ack = event.kind == Kind::Ack;
  return FrameAnswered{job.id(),
                       job.robot(),
                       event.frame_index,
                       event.attempt,
                       ack                        ? "ack"
                       : event.kind == Kind::Nack ? "nack"
                                                  : "none",
                       ack && event.frame && event.frame->authenticated,
                       event.response_time_ms};
}

}  // namespace

double Transmitter::audio_ms_of(double steady_ms) const { return steady_ms - mic_offset_ms_.load(); }

void Transmitter::publish_air(const Job& job, const ProgressEvent& event) {
  if (!air_events_.watched()) return;  // nobody to tell: no strings made on the sender's thread
  AirEvent air{audio_ms_of(event.at_ms), event.time, CommandEnded{}};
  switch (event.kind) {
    case Kind::Transmitting:
    case Kind::Retransmitting:
      if (!event.frame) return;
      air.what = frame_played(job, event);
      break;
    case Kind::Ack:
    case Kind::Nack:
    case Kind::NoAnswer:
      air.what = frame_answered(job, event);
      air.wall = store::WallClock::now();
      break;
    case Kind::WaitingForAir:
      air.what = AirWaiting{job.id(), job.robot(), event.air_wait_reason, event.air_wait_left_ms};
      break;
    case Kind::Confirmed:
    case Kind::Continued:
    case Kind::Failed:
    case Kind::Sent:
      air.what = CommandEnded{job.id(), job.robot(), job.description(), outcome_name(event.outcome), event.detail};
      air.wall = store::WallClock::now();
      break;
    default:  // Queued, AwaitingDecision: the caller's business, not the air's
      return;
  }
  air_events_.publish(std::move(air));
}

void Transmitter::publish_heard(const HeardAnswer& heard, double audio_ms, double level_dbfs) {
  if (!air_events_.watched()) return;
  const link::Answer& a = heard.answer;
  AnswerHeard answer{
      "", heard.link->profile().name, a.ack, std::nullopt, a.tag_reading.has_value(), std::nullopt, level_dbfs};
  if (a.sequence) answer.sequence = *a.sequence;
  if (!a.tag_reading && heard.link->addresses_robots()) {
    answer.address = a.address;
    for (RobotIndex r = 0; r < core_.robot_count(); ++r)  // names and addresses never change: no lock
      if (core_.robot_options(r).address == a.address) answer.robot = core_.robot_name(r);
  } else if (!heard.link->addresses_robots() && core_.robot_count() == 1) {
    answer.robot = core_.robot_name(0);  // the seed's answers name none: one robot's, if it is alone
  }
  air_events_.publish(AirEvent{audio_ms, store::WallClock::now(), std::move(answer)});
}

void Transmitter::publish_levels(std::span<const float> block, double end_audio_ms, bool busy, double level_dbfs,
                                 double floor_dbfs) {
  if (busy != air_busy_) {
    air_busy_ = busy;
    air_events_.publish(AirEvent{end_audio_ms, store::WallClock::now(), AirBusy{busy, level_dbfs, floor_dbfs}});
  }
  if (!air_events_.spectrum_watched()) {
    columns_.reset();  // nobody watches: no FFT runs
    return;
  }
  if (!columns_) {
    columns_ = std::make_unique<signal::SpectrumColumns>(profile().sample_rate_hz, kSpectrumLowHz, kSpectrumHighHz,
                                                         kMaxColumnBins, kMaxColumnsPerS);
    columns_start_ms_ = end_audio_ms - 1000.0 * static_cast<double>(block.size()) / profile().sample_rate_hz;
  }
  // A column's wall time is when its last sample reached the sender, as far as it can tell:
  // now, less the audio still queued behind this block (the device's and the capture
  // thread's) and the block's audio after the column. Stamped at the FFT instead, a watcher's
  // "air to page" delay would leave out the capture's own delay.
  const store::WallClock::time_point now = store::WallClock::now();
  const double queued_ms = microphone_->queued_ms();
  for (signal::ColumnLevels& c : columns_->feed(block)) {
    const double column_end_ms = columns_start_ms_ + c.end_audio_ms;
    const auto behind = std::chrono::duration<double, std::milli>(queued_ms + (end_audio_ms - column_end_ms));
    SpectrumColumn column{columns_->low_hz(), columns_->step_hz(), columns_->window_ms(), std::move(c.level_dbfs)};
    air_events_.publish_column(column_end_ms, now - std::chrono::duration_cast<store::WallClock::duration>(behind),
                               column);
  }
}

}  // namespace dtmf::server
