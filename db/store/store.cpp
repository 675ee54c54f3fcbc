#include "store.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdlib>
#include <pqxx/pqxx>

#include "user_dirs.h"

namespace dtmf::store {

namespace {

using SteadyClock = std::chrono::steady_clock;

// How long a stopping store goes on writing before it leaves the rest in the spill file.
constexpr std::chrono::seconds kStopWriteTime{1};

// SQLSTATE classes that mean "this row is wrong", not "the database is away": data
// exceptions, integrity violations, syntax / undefined objects, and store_rows' own RAISE.
bool is_data_error(const std::string& sqlstate) {
  const std::string cls = sqlstate.substr(0, 2);
  return cls == "22" || cls == "23" || cls == "42" || cls == "P0";
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

std::string default_spill_path(const std::string& program) {
  const std::string dir = program::user_state_dir().value_or("/tmp/dtmf-teleop-" + std::to_string(::getuid()));
  return dir + "/" + program + ".spill.jsonl";
}

Store::Store(StoreOptions options)
    : options_(std::move(options)),
      enabled_(!database_disabled(options_.database)),
      spill_(options_.spill_path.empty() ? default_spill_path("dtmf") : options_.spill_path),
      backoff_(options_.min_backoff) {
  if (!enabled_) {
    spdlog::info("no database (--db none): transmissions are not logged");
    return;
  }
  if (spill_.pending())
    spdlog::info("rows from an earlier run wait in {}; they go to the database first", spill_.path());
  worker_ = std::thread([this] { run(); });
}

Store::~Store() {
  if (!enabled_) return;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    stop_deadline_ = SteadyClock::now() + kStopWriteTime;
  }
  wake_.notify_all();
  worker_.join();
  if (spill_.pending()) spdlog::warn("database rows not yet written wait in {} for the next start", spill_.path());
}

void Store::enqueue(Table table, nlohmann::json row) {
  if (!enabled_) return;
  const auto now_us =
      std::chrono::duration_cast<std::chrono::microseconds>(WallClock::now().time_since_epoch()).count();
  std::string line;
  bool overflow = false;
  {
    std::lock_guard lock(mutex_);
    last_revision_ = std::max<std::int64_t>(last_revision_ + 1, now_us);
    row["revision"] = last_revision_;
    line = nlohmann::json{{"table", table_name(table)}, {"row", std::move(row)}}.dump();
    overflow = queue_.size() >= options_.memory_rows;
    if (!overflow) queue_.push_back(std::move(line));
  }
  if (overflow) {
    try {
      spill_.append(line);
      std::lock_guard lock(mutex_);
      ++stats_.spilled;
    } catch (const std::exception& e) {
      spdlog::error("a {} row is lost: {}", table_name(table), e.what());
      std::lock_guard lock(mutex_);
      ++stats_.rejected;
    }
  }
  wake_.notify_one();
}

bool Store::flush(std::chrono::milliseconds timeout) {
  if (!enabled_) return true;
  const auto deadline = SteadyClock::now() + timeout;
  std::unique_lock lock(mutex_);
  while (true) {
    if (queue_.empty() && !busy_ && !spill_.pending()) return true;
    if (SteadyClock::now() >= deadline) return false;
    wake_.notify_one();
    progress_.wait_for(lock, std::chrono::milliseconds(50));
  }
}

StoreStats Store::stats() const {
  std::lock_guard lock(mutex_);
  StoreStats s = stats_;
  s.queued = queue_.size();
  return s;
}

void Store::drop_connection(const std::string& why) {
  connection_.reset();
  next_attempt_ = SteadyClock::now() + backoff_;
  if (!outage_reported_) {
    spdlog::warn("database unavailable ({}); rows wait in {} until it returns", one_line(why), spill_.path());
    outage_reported_ = true;
  }
  std::lock_guard lock(mutex_);
  stats_.connected = false;
}

bool Store::ensure_connected() {
  if (connection_) return true;
  if (SteadyClock::now() < next_attempt_) return false;
  try {
    connection_ = connect(options_.database);
    migrate(*connection_);
  } catch (const std::exception& e) {
    drop_connection(e.what());
    backoff_ = std::min(backoff_ * 2, options_.max_backoff);
    return false;
  }
  if (outage_reported_) spdlog::info("database back: writing the rows that waited in {}", spill_.path());
  outage_reported_ = false;
  backoff_ = options_.min_backoff;
  std::lock_guard lock(mutex_);
  stats_.connected = true;
  return true;
}

bool Store::send(const std::vector<std::string>& lines) {
  if (lines.empty()) return true;
  std::string batch = "[";
  for (const std::string& line : lines) {
    if (batch.size() > 1) batch += ',';
    batch += line;
  }
  batch += ']';
  try {
    pqxx::work tx(*connection_);
    tx.exec_params("SELECT store_rows($1::jsonb)", batch);
    tx.commit();
  } catch (const pqxx::sql_error& e) {
    if (!connection_->is_open() || !is_data_error(e.sqlstate())) {
      drop_connection(e.what());
      return false;
    }
    // One bad row must not hold up the others: write them one by one, keep the bad ones.
    if (lines.size() > 1) {
      for (const std::string& line : lines) {
        if (!send({line})) return false;
      }
      return true;
    }
    spdlog::error("the database refused a row, kept in {}.rejected: {}", spill_.path(), one_line(e.what()));
    spill_.reject(lines.front(), one_line(e.what()));
    std::lock_guard lock(mutex_);
    ++stats_.rejected;
    return true;
  } catch (const std::exception& e) {
    drop_connection(e.what());
    return false;
  }
  std::lock_guard lock(mutex_);
  stats_.written += lines.size();
  return true;
}

bool Store::replay_spill() {
  while (true) {
    const std::vector<std::string> chunk = spill_.next_replay_chunk(options_.batch_rows);
    if (chunk.empty()) {
      spill_.replay_chunk_done();
      if (!spill_.pending()) return true;
      continue;
    }
    if (!send(chunk)) {
      spill_.replay_chunk_failed();
      return false;
    }
    spill_.replay_chunk_done();
    {
      std::lock_guard lock(mutex_);
      if (stopping_ && SteadyClock::now() >= stop_deadline_) return true;  // the rest waits for the next start
    }
    progress_.notify_all();
  }
}

void Store::run() {
  while (true) {
    // Newer rows wait while older ones (in the spill file) go first.
    if (ensure_connected() && spill_.pending()) replay_spill();

    std::vector<std::string> rows;
    {
      std::lock_guard lock(mutex_);
      const std::size_t take = connection_ ? std::min(options_.batch_rows, queue_.size()) : queue_.size();
      for (std::size_t i = 0; i < take; ++i) {
        rows.push_back(std::move(queue_.front()));
        queue_.pop_front();
      }
      busy_ = !rows.empty();
    }
    if (!rows.empty() && !(connection_ && send(rows))) {
      try {
        spill_.append(rows);
        std::lock_guard lock(mutex_);
        stats_.spilled += rows.size();
      } catch (const std::exception& e) {
        spdlog::error("{} database rows are lost: {}", rows.size(), e.what());
        std::lock_guard lock(mutex_);
        stats_.rejected += rows.size();
      }
    }

    std::unique_lock lock(mutex_);
    busy_ = false;
    progress_.notify_all();
    if (stopping_ && queue_.empty()) {
      // A clean stop tries the database once more, backoff or not, for the rows in the spill
      // file: a connection that broke unnoticed (the database restarted while we were idle)
      // fails on the last rows, and they would wait in the file for a next start.
      if (!spill_.pending() || last_try_made_ || SteadyClock::now() >= stop_deadline_) break;
      last_try_made_ = true;
      next_attempt_ = SteadyClock::now();
      continue;
    }
    if (!queue_.empty()) continue;
    if (connection_ && spill_.pending()) continue;
    // Nothing queued: sleep until a row comes, or until it is time to try the database again.
    const auto wake_at =
        (!connection_ && spill_.pending()) ? next_attempt_ : SteadyClock::now() + std::chrono::seconds(5);
    wake_.wait_until(lock, wake_at, [this] { return stopping_ || !queue_.empty(); });
  }
}

}  // namespace dtmf::store
