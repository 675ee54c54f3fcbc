#include "store_recorder.h"
#include "command/overloaded.h"

namespace dtmf::server {

namespace {

using Kind = ProgressEvent::Kind;

store::CommandRow command_row(const Job& job, const std::string& host, store::WallTime requested_at) {
  store::CommandRow row;
  row.id = job.id();
  row.run_id = job.run_id();
  row.kind = command::kind_name(job.command());
  row.parameters = nlohmann::json::object();
  auto& p = row.parameters;
  row.profile = job.profile().name;
  row.frame_count = job.frame_count();
  row.requested_at = requested_at;
  row.host = host;
  if (job.renewal()) {  // several robots' (migration 011): named in its parameters, not in `robot`
    row.kind = "renewal";
    p["robots"] = nlohmann::json::array();
    p["addresses"] = nlohmann::json::array();
    for (const Job::Renewed& r : job.renewed()) {
      p["robots"].push_back(r.robot);
      p["addresses"].push_back(r.address);
    }
    return row;
  }
  // Every alternative named: a new command that is not stored is a compile error here.
  std::visit(command::Overloaded{[](const command::Reset&) {}, [](const command::Stop&) {},
                                 [&](const command::DriveForDuration& c) {
                                   p["speed_percent"] = c.speed_percent;
                                   p["duration_s"] = c.duration_s;
                                 },
                                 [&](const command::TurnForDuration& c) {
                                   p["rotation_percent"] = c.rotation_percent;
                                   p["duration_s"] = c.duration_s;
                                 },
                                 [&](const command::DriveForward& c) { p["speed_percent"] = c.speed_percent; },
                                 [&](const command::Turn& c) { p["rotation_percent"] = c.rotation_percent; },
                                 [&](const command::Velocity& c) {
                                   p["linear_fraction"] = c.linear_fraction;
                                   p["angular_fraction"] = c.angular_fraction;
                                   p["lease_s"] = c.lease_s;
                                 }},
             job.command());
  row.every_robot = command::every_robot(job.command());
  if (!row.every_robot) {
    row.robot = job.robot();
    row.robot_address = job.link().options().address;
  }
  return row;
}

store::FrameAttemptRow attempt_row(const Job& job, const ProgressEvent& event) {
  const link::TransmitFrame& frame = *event.frame;
  store::FrameAttemptRow row;
  row.run_id = job.run_id();
  row.command_id = job.id();
  row.position = event.frame_index;
  row.attempt = event.attempt;
  if (frame.word) row.word = *frame.word;
  row.frame = frame.bits.decimal();
  row.authenticated = frame.authenticated;
  row.frame_width = frame.bit_count;
  row.tones_hz = frame.tones_hz;
  row.chord_started_at = event.time;
  row.air_wait_ms = event.air_wait_ms;
  if (!event.air_wait_reason.empty()) row.air_wait_reason = event.air_wait_reason;
  return row;
}

}  // namespace

store::CommandRow& TransmissionRecord::command_of(const Job& job, store::WallTime requested_at) {
  return commands_.try_emplace(job.id(), command_row(job, host_, requested_at)).first->second;
}

std::vector<TransmissionRecord::Row> TransmissionRecord::on_event(const Job& job, const ProgressEvent& event) {
  std::vector<Row> rows;
  switch (event.kind) {
    case Kind::Queued:
      rows.push_back(command_of(job, event.time));
      break;
    case Kind::Transmitting:
    case Kind::Retransmitting: {
      store::CommandRow& command = command_of(job, event.time);
      if (command.outcome == "queued" || command.frame_count != event.frame_count) {
        command.outcome = "transmitting";
        command.frame_count = event.frame_count;  // a counter synchronisation may have joined it
        rows.push_back(command);
      }
      rows.push_back(attempts_[job.id()] = attempt_row(job, event));
      break;
    }
    case Kind::Ack:
    case Kind::Nack:
    case Kind::NoAnswer: {
      const auto found = attempts_.find(job.id());
      if (found == attempts_.end()) break;  // an answer to no chord: nothing to complete
      store::FrameAttemptRow& attempt = found->second;
      attempt.chord_ended_at = event.chord_ended_at;
      attempt.answer = event.kind == Kind::Ack ? "ack" : event.kind == Kind::Nack ? "nack" : "none";
      attempt.answered_at = event.answered_at;
      rows.push_back(attempt);
      break;
    }
    case Kind::AwaitingDecision:
    case Kind::WaitingForAir:  // its attempt's row, when its chord starts, says how long it waited
      break;
    case Kind::Confirmed:
    case Kind::Continued:
    case Kind::Sent:
    case Kind::Failed: {
      store::CommandRow& command = command_of(job, event.time);
      command.finished_at = event.time;
      command.outcome = outcome_name(event.outcome);
      command.detail = event.detail;
      rows.push_back(command);
      commands_.erase(job.id());
      attempts_.erase(job.id());
      break;
    }
  }
  return rows;
}

void StoreRecorder::observe(const Job& job, const ProgressEvent& event) {
  std::lock_guard lock(mutex_);
  for (const auto& row : record_.on_event(job, event)) {
    std::visit([this](const auto& r) { store_.write(r); }, row);
  }
}

}  // namespace dtmf::server
