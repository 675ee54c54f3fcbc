#include "reception_reader.h"

#include <algorithm>
#include <pqxx/pqxx>

#include "field_values.h"

namespace dtmf::store {

namespace {

constexpr const char* kReceptionColumns =
    "stored, id::text AS id, coalesce(host, '') AS host, robot_address, profile, "
    "extract(epoch FROM heard_at) * 1000 AS heard_ms, crc_ok, coalesce(reply, '') AS reply, "
    "coalesce(event, '') AS event, coalesce(reason, '') AS reason, authenticated, coalesce(command, '') AS command, "
    "linear_mps, angular_rps";

ReceptionRecord reception_of(const pqxx::row& row) {
  ReceptionRecord r;
  r.stored = row["stored"].as<std::int64_t>();
  r.id = row["id"].as<std::string>();
  r.host = row["host"].as<std::string>();
  r.robot_address = optional_field<int>(row["robot_address"]);
  r.profile = row["profile"].as<std::string>();
  r.heard_unix_ms = row["heard_ms"].as<double>();
  r.crc_ok = row["crc_ok"].as<bool>();
  r.reply = row["reply"].as<std::string>();
  r.event = row["event"].as<std::string>();
  r.reason = row["reason"].as<std::string>();
  r.authenticated = row["authenticated"].as<bool>();
  r.command = row["command"].as<std::string>();
  r.linear_mps = optional_field<double>(row["linear_mps"]);
  r.angular_radps = optional_field<double>(row["angular_rps"]);
  return r;
}

// The run's span as SQL timestamps (its end NULL while it goes on); nullopt: no such run.
std::optional<pqxx::row> run_span(pqxx::read_transaction& tx, const RunSelector& which) {
  const std::string select = "SELECT started_at::text AS since, ended_at::text AS until FROM test_runs ";
  pqxx::result runs;
  if (const auto* id = std::get_if<std::string>(&which))
    runs = tx.exec_params(select + "WHERE id::text = $1", *id);
  else if (const auto* number = std::get_if<std::int64_t>(&which))
    runs = tx.exec_params(select + "WHERE number = $1", *number);
  else
    runs = tx.exec(select + "ORDER BY number DESC LIMIT 1");
  if (runs.empty()) return std::nullopt;
  return runs[0];
}

}  // namespace

std::optional<std::vector<ReceptionRecord>> ReceptionReader::list(const ReceptionQuery& query) const {
  auto connection = connect(database_);
  try {
    pqxx::read_transaction tx(*connection);
    std::optional<std::string> since, until;
    if (query.run) {
      const auto span = run_span(tx, *query.run);
      if (!span) return std::nullopt;
      since = (*span)["since"].as<std::string>();
      until = optional_field<std::string>((*span)["until"]);
    }
    // A robot's last frames of a run may be heard a little after its end: its ACK wait.
    const pqxx::result rows =
        tx.exec_params(std::string("SELECT ") + kReceptionColumns +
                           " FROM receptions WHERE stored > $1 AND ($2::smallint IS NULL OR robot_address = $2) "
                           "AND ($3::timestamptz IS NULL OR heard_at >= $3::timestamptz) "
                           "AND ($4::timestamptz IS NULL OR heard_at <= $4::timestamptz + interval '2 seconds') "
                           "ORDER BY stored DESC LIMIT $5",
                       query.after_stored, query.robot_address, since, until, query.limit);
    std::vector<ReceptionRecord> records;
    for (const auto& row : rows) records.push_back(reception_of(row));
    std::reverse(records.begin(), records.end());
    return records;
  } catch (const pqxx::failure& e) {
    throw DatabaseError(std::string("reading the receptions failed: ") + e.what());
  }
}

class ReceptionFeed::Receiver final : public pqxx::notification_receiver {
 public:
  explicit Receiver(pqxx::connection_base& c) : pqxx::notification_receiver(c, "dtmf_receptions") {}
  void operator()(const std::string&, int) override { announced = true; }
  bool announced = false;
};

ReceptionFeed::ReceptionFeed(const DatabaseUrl& database)
    : connection_(connect(database)), receiver_(std::make_unique<Receiver>(*connection_)) {}

ReceptionFeed::~ReceptionFeed() = default;

bool ReceptionFeed::wait(std::chrono::milliseconds timeout) {
  try {
    receiver_->announced = false;
    if (connection_->get_notifs() == 0) {
      const auto us = std::chrono::duration_cast<std::chrono::microseconds>(timeout).count();
      connection_->await_notification(static_cast<long>(us / 1000000), static_cast<long>(us % 1000000));
    }
    return std::exchange(receiver_->announced, false);
  } catch (const pqxx::failure& e) {
    throw DatabaseError(std::string("following the receptions failed: ") + e.what());
  }
}

}  // namespace dtmf::store
