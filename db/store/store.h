// Store library: logging rows to PostgreSQL without ever making the caller wait.
//
//   caller --write()--> bounded memory queue --worker thread--> store_rows() in PostgreSQL
//                              | full                  | database down
//                              v                       v
//                          spill file  <---------------+   (replayed, in order, on return)
//
// write() only serialises the row and queues it; when the queue is full the row goes to
// the spill file instead (a buffered append, no database I/O). The worker writes batches in
// transactions; when the database is unreachable it moves queued rows to the spill file and
// reconnects with exponential backoff; once connected it replays the spill file before
// newer rows. Every row is an upsert by id with a revision, so a replayed row is stored
// exactly once and an older version never overwrites a newer one. With no database
// (`--db none`) write() does nothing and the store says so once.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "database.h"
#include "rows.h"
#include "spill_file.h"

namespace dtmf::store {

struct StoreOptions {
  DatabaseUrl database;            // see database.h
  std::string spill_path;          // default: default_spill_path("dtmf")
  std::size_t memory_rows = 4096;  // queue capacity before rows spill
  std::size_t batch_rows = 500;    // rows per transaction
  std::chrono::milliseconds min_backoff{200};
  std::chrono::milliseconds max_backoff{5000};
};

// $XDG_STATE_HOME/dtmf-teleop/<program>.spill.jsonl, or ~/.local/state/..., or /tmp/...
std::string default_spill_path(const std::string& program);

struct StoreStats {
  std::size_t written = 0;   // rows the database has confirmed
  std::size_t spilled = 0;   // rows that went through the spill file
  std::size_t rejected = 0;  // rows the database refused for good (kept in <spill>.rejected)
  std::size_t queued = 0;    // rows in memory now
  bool connected = false;
};

class Store {
 public:
  explicit Store(StoreOptions options);
  ~Store();  // writes what it can within a second, spills the rest
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  void write(const TestRunRow& row) { enqueue(Table::TestRuns, to_json(row)); }
  void write(const CommandRow& row) { enqueue(Table::Commands, to_json(row)); }
  void write(const FrameAttemptRow& row) { enqueue(Table::FrameAttempts, to_json(row)); }
  void write(const ReceptionRow& row) { enqueue(Table::Receptions, to_json(row)); }

  // Waits until every row written so far is in the database (true), or the timeout passes.
  bool flush(std::chrono::milliseconds timeout);
  StoreStats stats() const;
  bool enabled() const { return enabled_; }

 private:
  void enqueue(Table table, nlohmann::json row);
  void run();
  bool ensure_connected();
  bool send(const std::vector<std::string>& lines);
  bool replay_spill();
  void drop_connection(const std::string& why);

  StoreOptions options_;
  bool enabled_;
  SpillFile spill_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable progress_;
  std::deque<std::string> queue_;
  std::int64_t last_revision_ = 0;
  bool stopping_ = false;
  std::chrono::steady_clock::time_point stop_deadline_{};  // set with stopping_
  bool busy_ = false;                                      // the worker holds rows taken from the queue
  StoreStats stats_;

  // The worker's own.
  std::unique_ptr<pqxx::connection> connection_;
  std::chrono::steady_clock::time_point next_attempt_{};
  std::chrono::milliseconds backoff_;
  bool outage_reported_ = false;
  bool last_try_made_ = false;  // the stop's one try past the backoff
  std::thread worker_;
};

}  // namespace dtmf::store
