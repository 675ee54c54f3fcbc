#include "run_reader.h"

#include <pqxx/pqxx>

#include <sstream>
#include "field_values.h"

namespace dtmf::store {

namespace {

constexpr const char* kRunColumns =
    "id::text AS id, number, label, profile, extract(epoch FROM started_at) * 1000 AS started_ms, "
    "extract(epoch FROM ended_at) * 1000 AS ended_ms, transmissions_sent, array_to_string(robots, ' ') AS robots";

constexpr const char* kFrameColumns =
    "command_id::text AS command_id, coalesce(command_kind, '') AS command, position, attempt, word, "
    "frame_bits, array_to_string(tones_hz, ' ') AS tones, extract(epoch FROM chord_started_at) * 1000 AS started_ms, "
    "coalesce(answer, '') AS answer, response_time_ms, latency_ms";

RunSummary run_of(const pqxx::row& row) {
  RunSummary run;
  run.id = row["id"].as<std::string>();
  run.number = row["number"].as<std::int64_t>();
  run.label = row["label"].as<std::string>();
  run.profile = row["profile"].as<std::string>();
  run.started_unix_ms = row["started_ms"].as<double>();
  run.ended_unix_ms = optional_field<double>(row["ended_ms"]);
  run.transmissions_sent = row["transmissions_sent"].as<std::int64_t>();
  std::istringstream robots(row["robots"].as<std::string>());  // names have no spaces (robot_roster.h)
  for (std::string name; robots >> name;) run.robots.push_back(name);
  return run;
}

FrameRecord frame_of(const pqxx::row& row) {
  FrameRecord frame;
  frame.command_id = row["command_id"].as<std::string>();
  frame.command = row["command"].as<std::string>();
  frame.position = row["position"].as<std::uint32_t>();
  frame.attempt = row["attempt"].as<std::uint32_t>();
  frame.word = optional_field<std::uint32_t>(row["word"]);
  frame.frame_bits = row["frame_bits"].as<std::string>();
  std::istringstream tones(row["tones"].as<std::string>());
  for (double hz; tones >> hz;) frame.tones_hz.push_back(hz);
  frame.chord_started_unix_ms = row["started_ms"].as<double>();
  frame.answer = row["answer"].as<std::string>();
  frame.response_time_ms = optional_field<double>(row["response_time_ms"]);
  frame.latency_ms = optional_field<double>(row["latency_ms"]);
  return frame;
}

void fill_figures(RunReport& report, const pqxx::row& r) {
  const auto count = [&](const char* column) { return r[column].is_null() ? 0 : r[column].as<std::int64_t>(); };
  const auto measure = [&](const char* column) { return optional_field<double>(r[column]); };
  report.transmissions_sent = count("transmissions_sent");
  report.frame_attempts = count("frame_attempts");
  report.transmissions_received = count("transmissions_received");
  report.successfully_matched = count("successfully_matched");
  report.dropped = count("dropped");
  report.false_positives = count("false_positives");
  report.false_positive_rate_pct = measure("false_positive_rate_pct");
  report.duplicates = count("duplicates");
  report.successful_transmissions = count("successful_transmissions");
  report.success_rate_pct = measure("success_rate_pct");
  report.sender_confirmed = count("sender_confirmed");
  report.sender_confirmed_rate_pct = measure("sender_confirmed_rate_pct");
  report.crc_accepted = count("crc_accepted");
  report.crc_rejected = count("crc_rejected");
  report.negative_confirmations_sent = count("negative_confirmations_sent");
  report.error_catch_rate_pct = measure("error_catch_rate_pct");
  report.refused = count("refused");
  report.refused_authentication = count("refused_authentication");
  report.sender_confirmed_unauthenticated = count("sender_confirmed_unauthenticated");
  report.refused_authentication_peak_per_minute = count("refused_authentication_peak_per_minute");
  report.response_time_avg_ms = measure("response_time_avg_ms");
  report.response_time_min_ms = measure("response_time_min_ms");
  report.response_time_max_ms = measure("response_time_max_ms");
  report.latency_avg_ms = measure("latency_avg_ms");
  report.latency_min_ms = measure("latency_min_ms");
  report.latency_max_ms = measure("latency_max_ms");
  report.robot = optional_field<std::string>(r["robot"]);
  report.every_robot_stops_sent = count("every_robot_stops_sent");
  report.every_robot_stops_executed = count("every_robot_stops_executed");
  report.renewals_sent = count("renewals_sent");
  report.renewals_executed = count("renewals_executed");
  report.air_waits = count("air_waits");
  report.air_wait_total_ms = measure("air_wait_total_ms").value_or(0);
  report.air_wait_max_ms = measure("air_wait_max_ms");
}

// pqxx's own errors become DatabaseError, which says what to do.
template <typename F>
auto with_database(const DatabaseUrl& database, F&& body) {
  auto connection = connect(database);
  try {
    pqxx::read_transaction tx(*connection);
    return body(tx);
  } catch (const pqxx::failure& e) {
    throw DatabaseError(std::string("reading the test runs failed: ") + e.what());
  }
}

}  // namespace

std::vector<RunSummary> RunReader::list_runs(int limit) const {
  return with_database(database_, [&](pqxx::read_transaction& tx) {
    std::string sql = std::string("SELECT ") + kRunColumns + " FROM runs ORDER BY number DESC";
    if (limit > 0) sql += " LIMIT " + std::to_string(limit);
    std::vector<RunSummary> runs;
    for (const auto& row : tx.exec(sql)) runs.push_back(run_of(row));
    return runs;
  });
}

std::optional<RunReport> RunReader::report(const RunSelector& which, bool include_frames,
                                           const std::optional<std::string>& robot) const {
  return with_database(database_, [&](pqxx::read_transaction& tx) -> std::optional<RunReport> {
    const std::string select = std::string("SELECT ") + kRunColumns + " FROM runs ";
    pqxx::result runs;
    if (const auto* id = std::get_if<std::string>(&which)) {
      runs = tx.exec_params(select + "WHERE id::text = $1", *id);
    } else if (const auto* number = std::get_if<std::int64_t>(&which)) {
      runs = tx.exec_params(select + "WHERE number = $1", *number);
    } else {
      runs = tx.exec(select + "ORDER BY number DESC LIMIT 1");
    }
    if (runs.empty()) return std::nullopt;
    RunReport report;
    report.run = run_of(runs[0]);
    fill_figures(report, robot
                             ? tx.exec_params("SELECT * FROM run_report($1::uuid, $2::text)", report.run.id, *robot)[0]
                             : tx.exec_params("SELECT * FROM run_report($1::uuid)", report.run.id)[0]);
    if (include_frames) {
      for (const auto& row :
           tx.exec_params(std::string("SELECT ") + kFrameColumns +
                              " FROM run_frames($1::uuid) f WHERE $2::text IS NULL OR f.command_id IN "
                              "(SELECT id FROM commands WHERE robot = $2::text)",
                          report.run.id, robot)) {
        report.frames.push_back(frame_of(row));
      }
    }
    return report;
  });
}

}  // namespace dtmf::store
