// Store library, the read side: test runs and their seed-style reports, as plain values.
//
// The figures come from the database's own views and functions (db/migrations: `runs`,
// run_report(), run_frames()), so every reader gets the report SQL computes; this class only
// selects and converts. Whoever serves them (the server's ListRuns and GetReport) needs no
// SQL of its own. Each call opens its own connection and throws DatabaseError when the
// database cannot answer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "database.h"

namespace dtmf::store {

struct RunSummary {
  std::string id;
  std::int64_t number = 0;
  std::string label;
  std::string profile;
  double started_unix_ms = 0;
  std::optional<double> ended_unix_ms;  // nullopt while the run goes on
  std::int64_t transmissions_sent = 0;
  std::vector<std::string> robots;  // named by its commands (migration 010)
};

// One frame attempt of a run, with the robot's side matched to it (run_frames()).
struct FrameRecord {
  std::string command_id;
  std::string command;  // kind, "" if unknown
  std::uint32_t position = 0;
  std::uint32_t attempt = 0;
  std::optional<std::uint32_t> word;
  std::string frame_bits;
  std::vector<double> tones_hz;
  double chord_started_unix_ms = 0;
  std::string answer;  // ack, nack, none, or ""
  std::optional<double> response_time_ms;
  std::optional<double> latency_ms;
};

// run_report()'s columns: counts, and figures that are absent when nothing was measured.
struct RunReport {
  RunSummary run;
  std::int64_t transmissions_sent = 0, frame_attempts = 0, transmissions_received = 0, successfully_matched = 0,
               dropped = 0, false_positives = 0, duplicates = 0, successful_transmissions = 0, sender_confirmed = 0,
               crc_accepted = 0, crc_rejected = 0, negative_confirmations_sent = 0;
  // Intact frames the robot refused (migration 007), and those for authentication.
  std::int64_t refused = 0, refused_authentication = 0;
  // Confirmed by an untagged ACK, and the most authentication refusals in 60 s (migration 009).
  std::int64_t sender_confirmed_unauthenticated = 0, refused_authentication_peak_per_minute = 0;
  std::optional<double> false_positive_rate_pct, success_rate_pct, sender_confirmed_rate_pct, error_catch_rate_pct,
      response_time_avg_ms, response_time_min_ms, response_time_max_ms, latency_avg_ms, latency_min_ms, latency_max_ms;
  std::vector<FrameRecord> frames;   // with include_frames only
  std::optional<std::string> robot;  // the robot reported; none: the whole room (migration 010)
  std::int64_t every_robot_stops_sent = 0, every_robot_stops_executed = 0;
  // Joint renewals (migration 011): sent naming this robot (all, for the room), and taken.
  std::int64_t renewals_sent = 0, renewals_executed = 0;
  // Waits for the air (migration 014): frames that waited, all their waits, and the longest
  // any one command waited, its frames together (none: no command waited).
  std::int64_t air_waits = 0;
  double air_wait_total_ms = 0;
  std::optional<double> air_wait_max_ms;
};

// Which run: the newest (monostate), by id, or by number.
using RunSelector = std::variant<std::monostate, std::string, std::int64_t>;

class RunReader {
 public:
  explicit RunReader(DatabaseUrl database) : database_(std::move(database)) {}

  // Newest first; limit 0: all.
  std::vector<RunSummary> list_runs(int limit) const;
  // nullopt: no such run. `robot`: one robot's figures and frames (run_report(run, robot)).
  std::optional<RunReport> report(const RunSelector& which, bool include_frames,
                                  const std::optional<std::string>& robot = std::nullopt) const;

 private:
  DatabaseUrl database_;
};

}  // namespace dtmf::store
