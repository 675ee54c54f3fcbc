// TeleopService: labelled test runs, and their seed-style reports read through the store
// (store::RunReader: the SQL is the store's, this file only maps its values to messages).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "database_status.h"
#include "run_reader.h"
#include "teleop_service.h"

namespace dtmf::server {

namespace {

void fill_run(v1::Run& run, const store::RunSummary& summary) {
  run.set_run_id(summary.id);
  run.set_number(summary.number);
  run.set_label(summary.label);
  run.set_profile(summary.profile);
  run.set_started_unix_ms(static_cast<std::int64_t>(summary.started_unix_ms));
  run.set_ended_unix_ms(summary.ended_unix_ms ? static_cast<std::int64_t>(*summary.ended_unix_ms) : 0);
  run.set_transmissions_sent(summary.transmissions_sent);
  for (const auto& robot : summary.robots) run.add_robots(robot);
}

void fill_frame(v1::FrameRecord& frame, const store::FrameRecord& record) {
  frame.set_command_id(record.command_id);
  frame.set_command(record.command);
  frame.set_position(record.position);
  frame.set_attempt(record.attempt);
  if (record.word) frame.set_word(*record.word);
  frame.set_frame_bits(record.frame_bits);
  for (double hz : record.tones_hz) frame.add_tones_hz(hz);
  frame.set_chord_started_unix_ms(std::llround(record.chord_started_unix_ms));
  frame.set_answer(record.answer);
  if (record.response_time_ms) frame.set_response_time_ms(*record.response_time_ms);
  if (record.latency_ms) frame.set_latency_ms(*record.latency_ms);
}

void fill_report(v1::GetReportResponse& response, const store::RunReport& report) {
  fill_run(*response.mutable_run(), report.run);
  response.set_transmissions_sent(report.transmissions_sent);
  response.set_frame_attempts(report.frame_attempts);
  response.set_transmissions_received(report.transmissions_received);
  response.set_successfully_matched(report.successfully_matched);
  response.set_dropped(report.dropped);
  response.set_false_positives(report.false_positives);
  response.set_duplicates(report.duplicates);
  response.set_successful_transmissions(report.successful_transmissions);
  response.set_sender_confirmed(report.sender_confirmed);
  response.set_crc_accepted(report.crc_accepted);
  response.set_crc_rejected(report.crc_rejected);
  response.set_negative_confirmations_sent(report.negative_confirmations_sent);
  response.set_refused(report.refused);
  response.set_refused_authentication(report.refused_authentication);
  response.set_sender_confirmed_unauthenticated(report.sender_confirmed_unauthenticated);
  response.set_refused_authentication_peak_per_minute(report.refused_authentication_peak_per_minute);
  response.set_robot(report.robot.value_or(""));
  response.set_every_robot_stops_sent(report.every_robot_stops_sent);
  response.set_every_robot_stops_executed(report.every_robot_stops_executed);
  response.set_renewals_sent(report.renewals_sent);
  response.set_renewals_executed(report.renewals_executed);
  response.set_air_waits(report.air_waits);
  response.set_air_wait_total_ms(report.air_wait_total_ms);
  using R = v1::GetReportResponse;
  const auto measure = [&](const std::optional<double>& value, void (R::*setter)(double)) {
    if (value) (response.*setter)(*value);
  };
  measure(report.false_positive_rate_pct, &R::set_false_positive_rate_pct);
  measure(report.success_rate_pct, &R::set_success_rate_pct);
  measure(report.sender_confirmed_rate_pct, &R::set_sender_confirmed_rate_pct);
  measure(report.error_catch_rate_pct, &R::set_error_catch_rate_pct);
  measure(report.response_time_avg_ms, &R::set_response_time_avg_ms);
  measure(report.response_time_min_ms, &R::set_response_time_min_ms);
  measure(report.response_time_max_ms, &R::set_response_time_max_ms);
  measure(report.latency_avg_ms, &R::set_latency_avg_ms);
  measure(report.latency_min_ms, &R::set_latency_min_ms);
  measure(report.latency_max_ms, &R::set_latency_max_ms);
  measure(report.air_wait_max_ms, &R::set_air_wait_max_ms);
  for (const auto& frame : report.frames) fill_frame(*response.add_frames(), frame);
}

}  // namespace

grpc::Status TeleopService::start_run(const std::string& label, const std::string& notes, const LinkProfile& profile,
                                      std::string& run_id) {
  std::lock_guard lock(runs_mutex_);
  if (active_run_) {
    return {grpc::StatusCode::FAILED_PRECONDITION,
            "run '" + active_run_->label + "' (" + active_run_->id + ") is still going: EndRun it first"};
  }
  store::TestRunRow run;
  run.label = label;
  run.notes = notes;
  run.profile = profile.name;
  run.started_at = store::WallClock::now();
  run.host = options_.host;
  store_.write(run);
  transmitter_.set_run(run.id);
  run_id = run.id;
  active_run_ = run;
  spdlog::info("test run '{}' started ({})", label, run.id);
  return grpc::Status::OK;
}

grpc::Status TeleopService::end_run(const std::string& run_id) {
  std::lock_guard lock(runs_mutex_);
  if (!active_run_ || active_run_->id != run_id) {
    return {grpc::StatusCode::NOT_FOUND, "no test run " + run_id + " is going on"};
  }
  active_run_->ended_at = store::WallClock::now();
  store_.write(*active_run_);
  transmitter_.set_run(std::nullopt);
  spdlog::info("test run '{}' ended ({})", active_run_->label, run_id);
  active_run_.reset();
  return grpc::Status::OK;
}

grpc::Status TeleopService::StartRun(grpc::ServerContext*, const v1::StartRunRequest* request,
                                     v1::StartRunResponse* response) {
  try {
    check_label("label", request->label());
    check_text("notes", request->notes(), kNotesLimit);
  } catch (const RequestError& e) {
    return e.status();
  }
  std::string run_id;
  auto status = start_run(request->label(), request->notes(), transmitter_.profile(), run_id);
  response->set_run_id(run_id);
  return status;
}

grpc::Status TeleopService::EndRun(grpc::ServerContext*, const v1::EndRunRequest* request, v1::EndRunResponse*) {
  if (request->run_id().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "run_id: required (from StartRun)"};
  try {
    check_text("run_id", request->run_id(), kIdLimit);
  } catch (const RequestError& e) {
    return e.status();
  }
  return end_run(request->run_id());
}

grpc::Status TeleopService::ListRuns(grpc::ServerContext*, const v1::ListRunsRequest* request,
                                     v1::ListRunsResponse* response) {
  if (store::database_disabled(options_.database)) return no_database();
  store_.flush(std::chrono::seconds(5));
  try {
    for (const auto& run : store::RunReader(options_.database).list_runs(request->limit())) {
      fill_run(*response->add_runs(), run);
    }
    return grpc::Status::OK;
  } catch (const std::exception& e) {
    return database_trouble(e);
  }
}

grpc::Status TeleopService::GetReport(grpc::ServerContext*, const v1::GetReportRequest* request,
                                      v1::GetReportResponse* response) {
  try {
    check_text("run_id", request->run_id(), kIdLimit);
    check_text("robot", request->robot(), kIdLimit);
  } catch (const RequestError& e) {
    return e.status();
  }
  if (store::database_disabled(options_.database)) return no_database();
  store_.flush(std::chrono::seconds(5));  // the run's last rows first
  const std::optional<std::string> robot =
      request->robot().empty() ? std::nullopt : std::optional<std::string>(request->robot());
  store::RunSelector which;
  if (request->run_case() == v1::GetReportRequest::kRunId) which = request->run_id();
  if (request->run_case() == v1::GetReportRequest::kRunNumber) which = std::int64_t{request->run_number()};
  try {
    const auto report = store::RunReader(options_.database).report(which, request->include_frames(), robot);
    if (!report) return {grpc::StatusCode::NOT_FOUND, "no such test run (see ListRuns)"};
    const auto& named = report->run.robots;
    if (robot && std::find(named.begin(), named.end(), *robot) == named.end()) {
      std::string all;
      for (const auto& n : named) all += (all.empty() ? "" : ", ") + n;
      return {grpc::StatusCode::NOT_FOUND, "robot: no command of run " + std::to_string(report->run.number) +
                                               " named robot \"" + *robot +
                                               "\" (its robots: " + (all.empty() ? "none named" : all) + ")"};
    }
    fill_report(*response, *report);
    return grpc::Status::OK;
  } catch (const std::exception& e) {
    return database_trouble(e);
  }
}

}  // namespace dtmf::server
