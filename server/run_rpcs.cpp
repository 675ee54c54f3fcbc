// TeleopService: labelled test runs, and their seed-style reports read from the database.
#include <spdlog/spdlog.h>

#include <cmath>
#include <sstream>
#include <pqxx/pqxx>

#include "teleop_service.h"

namespace dtmf::server {

namespace {

void fill_run(v1::Run& run, const pqxx::row& row) {
  run.set_run_id(row["id"].as<std::string>());
  run.set_number(row["number"].as<std::int64_t>());
  run.set_label(row["label"].as<std::string>());
  run.set_profile(row["profile"].as<std::string>());
  run.set_started_unix_ms(static_cast<std::int64_t>(row["started_ms"].as<double>()));
  run.set_ended_unix_ms(row["ended_ms"].is_null() ? 0 : static_cast<std::int64_t>(row["ended_ms"].as<double>()));
  run.set_transmissions_sent(row["transmissions_sent"].as<std::int64_t>());
}

constexpr const char* kRunColumns =
    "id::text AS id, number, label, profile, extract(epoch FROM started_at) * 1000 AS started_ms, "
    "extract(epoch FROM ended_at) * 1000 AS ended_ms, transmissions_sent";

constexpr const char* kFrameColumns =
    "command_id::text AS command_id, coalesce(command_kind, '') AS command, position, attempt, word, "
    "frame_bits, array_to_string(tones_hz, ' ') AS tones, extract(epoch FROM chord_started_at) * 1000 AS started_ms, "
    "coalesce(answer, '') AS answer, response_time_ms, latency_ms";

void fill_frame(v1::FrameRecord& frame, const pqxx::row& row) {
  frame.set_command_id(row["command_id"].as<std::string>());
  frame.set_command(row["command"].as<std::string>());
  frame.set_position(row["position"].as<std::uint32_t>());
  frame.set_attempt(row["attempt"].as<std::uint32_t>());
  if (!row["word"].is_null()) frame.set_word(row["word"].as<std::uint32_t>());
  frame.set_frame_bits(row["frame_bits"].as<std::string>());
  std::istringstream tones(row["tones"].as<std::string>());
  for (double hz; tones >> hz;) frame.add_tones_hz(hz);
  frame.set_chord_started_unix_ms(std::llround(row["started_ms"].as<double>()));
  frame.set_answer(row["answer"].as<std::string>());
  if (!row["response_time_ms"].is_null()) frame.set_response_time_ms(row["response_time_ms"].as<double>());
  if (!row["latency_ms"].is_null()) frame.set_latency_ms(row["latency_ms"].as<double>());
}

grpc::Status no_database() {
  return {grpc::StatusCode::FAILED_PRECONDITION,
          "this server runs without a database (--db none): there are no runs or reports; start it with --db URL"};
}

grpc::Status database_trouble(const std::exception& e) {
  return {grpc::StatusCode::UNAVAILABLE, std::string("the database cannot answer: ") + e.what()};
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

grpc::Status TeleopService::StartRun(grpc::ServerContext* context, const v1::StartRunRequest* request,
                                     v1::StartRunResponse* response) {
  if (auto denied = authorize(context); !denied.ok()) return denied;
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

grpc::Status TeleopService::EndRun(grpc::ServerContext* context, const v1::EndRunRequest* request, v1::EndRunResponse*) {
  if (auto denied = authorize(context); !denied.ok()) return denied;
  if (request->run_id().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "run_id: required (from StartRun)"};
  try {
    check_text("run_id", request->run_id(), kIdLimit);
  } catch (const RequestError& e) {
    return e.status();
  }
  return end_run(request->run_id());
}

grpc::Status TeleopService::ListRuns(grpc::ServerContext* context, const v1::ListRunsRequest* request,
                                     v1::ListRunsResponse* response) {
  if (auto denied = authorize(context); !denied.ok()) return denied;
  if (store::database_disabled(options_.database)) return no_database();
  store_.flush(std::chrono::seconds(5));
  try {
    auto connection = store::connect(options_.database);
    pqxx::work tx(*connection);
    std::string sql = std::string("SELECT ") + kRunColumns + " FROM runs ORDER BY number DESC";
    if (request->limit() > 0) sql += " LIMIT " + std::to_string(request->limit());
    for (const auto& row : tx.exec(sql)) fill_run(*response->add_runs(), row);
    return grpc::Status::OK;
  } catch (const std::exception& e) {
    return database_trouble(e);
  }
}

grpc::Status TeleopService::GetReport(grpc::ServerContext* context, const v1::GetReportRequest* request,
                                      v1::GetReportResponse* response) {
  if (auto denied = authorize(context); !denied.ok()) return denied;
  try {
    check_text("run_id", request->run_id(), kIdLimit);
  } catch (const RequestError& e) {
    return e.status();
  }
  if (store::database_disabled(options_.database)) return no_database();
  store_.flush(std::chrono::seconds(5));  // the run's last rows first
  try {
    auto connection = store::connect(options_.database);
    pqxx::work tx(*connection);
    pqxx::result runs;
    const std::string select = std::string("SELECT ") + kRunColumns + " FROM runs ";
    switch (request->run_case()) {
      case v1::GetReportRequest::kRunId:
        runs = tx.exec_params(select + "WHERE id::text = $1", request->run_id());
        break;
      case v1::GetReportRequest::kRunNumber:
        runs = tx.exec_params(select + "WHERE number = $1", request->run_number());
        break;
      default:
        runs = tx.exec(select + "ORDER BY number DESC LIMIT 1");
    }
    if (runs.empty()) return {grpc::StatusCode::NOT_FOUND, "no such test run (see ListRuns)"};
    fill_run(*response->mutable_run(), runs[0]);
    const pqxx::row r = tx.exec_params("SELECT * FROM run_report($1::uuid)", response->run().run_id())[0];
    const auto count = [&](const char* column) { return r[column].is_null() ? 0 : r[column].as<std::int64_t>(); };
    const auto measure = [&](const char* column, auto setter) {
      if (!r[column].is_null()) (response->*setter)(r[column].as<double>());
    };
    using R = v1::GetReportResponse;
    response->set_transmissions_sent(count("transmissions_sent"));
    response->set_frame_attempts(count("frame_attempts"));
    response->set_transmissions_received(count("transmissions_received"));
    response->set_successfully_matched(count("successfully_matched"));
    response->set_dropped(count("dropped"));
    response->set_false_positives(count("false_positives"));
    measure("false_positive_rate_pct", &R::set_false_positive_rate_pct);
    response->set_duplicates(count("duplicates"));
    response->set_successful_transmissions(count("successful_transmissions"));
    measure("success_rate_pct", &R::set_success_rate_pct);
    response->set_sender_confirmed(count("sender_confirmed"));
    measure("sender_confirmed_rate_pct", &R::set_sender_confirmed_rate_pct);
    response->set_crc_accepted(count("crc_accepted"));
    response->set_crc_rejected(count("crc_rejected"));
    response->set_negative_confirmations_sent(count("negative_confirmations_sent"));
    measure("error_catch_rate_pct", &R::set_error_catch_rate_pct);
    measure("response_time_avg_ms", &R::set_response_time_avg_ms);
    measure("response_time_min_ms", &R::set_response_time_min_ms);
    measure("response_time_max_ms", &R::set_response_time_max_ms);
    measure("latency_avg_ms", &R::set_latency_avg_ms);
    measure("latency_min_ms", &R::set_latency_min_ms);
    measure("latency_max_ms", &R::set_latency_max_ms);
    if (request->include_frames()) {
      const auto frames = tx.exec_params(std::string("SELECT ") + kFrameColumns + " FROM run_frames($1::uuid)",
                                         response->run().run_id());
      for (const auto& row : frames) fill_frame(*response->add_frames(), row);
    }
    return grpc::Status::OK;
  } catch (const std::exception& e) {
    return database_trouble(e);
  }
}

}  // namespace dtmf::server
