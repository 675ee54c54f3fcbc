// Store library, the read side: what robots heard and did (the receptions every dtmf-agent
// logs), listed and followed.
//
// ReceptionReader lists them in the order they were stored (migration 015's `stored`), for a
// robot's address and within a run's time if asked. ReceptionFeed LISTENs on the channel each
// stored reception is announced on, so that a follower reads again only when there is
// something new. Both open connections of their own and throw DatabaseError when the
// database cannot answer.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "database.h"
#include "run_reader.h"

namespace dtmf::store {

struct ReceptionRecord {
  std::int64_t stored = 0;
  std::string id;
  std::string host;
  std::optional<int> robot_address;
  std::string profile;
  double heard_unix_ms = 0;
  bool crc_ok = false;
  std::string reply;   // ack, nack, or ""
  std::string event;   // link::event_name; "" for a broken frame
  std::string reason;  // why a refused frame was refused
  bool authenticated = false;
  std::string command;
  std::optional<double> linear_mps;
  std::optional<double> angular_radps;
};

struct ReceptionQuery {
  std::optional<int> robot_address;  // none: every robot
  std::optional<RunSelector> run;    // none: any time
  int limit = 100;                   // the newest this many
  std::int64_t after_stored = 0;     // only those stored after this one
};

class ReceptionReader {
 public:
  explicit ReceptionReader(DatabaseUrl database) : database_(std::move(database)) {}
  // Oldest first; nullopt when the run asked for does not exist.
  std::optional<std::vector<ReceptionRecord>> list(const ReceptionQuery& query) const;

 private:
  DatabaseUrl database_;
};

class ReceptionFeed {
 public:
  explicit ReceptionFeed(const DatabaseUrl& database);
  ~ReceptionFeed();
  // Waits up to `timeout` for a reception stored since the last call; whether one was.
  bool wait(std::chrono::milliseconds timeout);

 private:
  class Receiver;
  std::unique_ptr<pqxx::connection> connection_;
  std::unique_ptr<Receiver> receiver_;
};

}  // namespace dtmf::store
