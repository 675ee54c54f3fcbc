#include "database.h"

#include <algorithm>
#include <cstdlib>
#include <pqxx/pqxx>
#include <regex>

namespace dtmf::store {

namespace {
// pg_advisory_xact_lock key: "dtmf" in ASCII, then 1 for migrations.
constexpr long long kMigrationLock = 0x64746d6600000001LL;
constexpr const char* kConnectTimeoutS = "3";
}  // namespace

DatabaseUrl parse_database_flag(const std::optional<std::string>& flag) {
  if (!flag) return std::nullopt;
  if (*flag == "none") return std::string();
  return *flag;
}

bool database_disabled(const DatabaseUrl& url) { return url && url->empty(); }

std::string describe_database(const DatabaseUrl& url) {
  if (!url) {
    std::string text = "the libpq environment";
    for (const char* name : {"PGHOST", "PGPORT", "PGDATABASE", "PGUSER"}) {
      if (const char* value = std::getenv(name)) text += std::string(" ") + name + "=" + value;
    }
    return text;
  }
  if (url->empty()) return "no database";
  // Hide a password in a URL (postgresql://user:secret@host) or a key=value string.
  std::string shown = std::regex_replace(*url, std::regex(R"(://([^:/@]+):[^@]*@)"), "://$1:***@");
  return std::regex_replace(shown, std::regex(R"(password\s*=\s*\S+)"), "password=***");
}

namespace {

// The connection string with a connect timeout, unless it (or PGCONNECT_TIMEOUT) has one.
std::string with_timeout(const DatabaseUrl& url) {
  std::string conninfo = url.value_or("");
  if (conninfo.find("connect_timeout") != std::string::npos || std::getenv("PGCONNECT_TIMEOUT")) return conninfo;
  const bool is_url = conninfo.rfind("postgres://", 0) == 0 || conninfo.rfind("postgresql://", 0) == 0;
  if (is_url)
    return conninfo + (conninfo.find('?') == std::string::npos ? "?" : "&") + "connect_timeout=" + kConnectTimeoutS;
  return conninfo + (conninfo.empty() ? "" : " ") + "connect_timeout=" + kConnectTimeoutS;
}

}  // namespace

std::unique_ptr<pqxx::connection> connect(const DatabaseUrl& url) {
  try {
    return std::make_unique<pqxx::connection>(with_timeout(url));
  } catch (const std::exception& e) {
    // libpq's messages span lines ("...failed: ...\n\tIs the server running..."): keep one.
    std::string why = std::regex_replace(std::string(e.what()), std::regex(R"(\s*\n\s*)"), " ");
    while (!why.empty() && why.back() == ' ') why.pop_back();
    throw DatabaseError("cannot reach the database (" + describe_database(url) + "): " + why +
                        " — start PostgreSQL (e.g. scripts/pg start), fix --db, or run with --db none");
  }
}

int schema_version(pqxx::connection& connection) {
  pqxx::work tx(connection);
  const pqxx::result exists = tx.exec("SELECT to_regclass('schema_migrations') IS NOT NULL");
  if (!exists[0][0].as<bool>()) return 0;
  return tx.exec("SELECT coalesce(max(version), 0) FROM schema_migrations")[0][0].as<int>();
}

MigrationResult migrate(pqxx::connection& connection) {
  const auto& migrations = known_migrations();
  const int newest = migrations.empty() ? 0 : migrations.back().version;
  MigrationResult result{0, 0, {}};
  try {
    pqxx::work tx(connection);
    tx.exec("SELECT pg_advisory_xact_lock(" + std::to_string(kMigrationLock) + ")");
    tx.exec(
        "CREATE TABLE IF NOT EXISTS schema_migrations ("
        " version integer PRIMARY KEY, name text NOT NULL,"
        " applied_at timestamptz NOT NULL DEFAULT now())");
    const pqxx::result applied = tx.exec("SELECT version, name FROM schema_migrations ORDER BY version");
    for (const auto& row : applied) {
      const int version = row[0].as<int>();
      result.version_before = std::max(result.version_before, version);
      if (version > newest) {
        throw DatabaseError("the database schema is at version " + std::to_string(version) + " (" +
                            row[1].as<std::string>() + "), newer than this program knows (" + std::to_string(newest) +
                            "): upgrade dtmf-teleop, or use another database");
      }
    }
    for (const Migration& m : migrations) {
      if (m.version <= result.version_before) continue;
      tx.exec(std::string(m.sql));
      tx.exec_params("INSERT INTO schema_migrations (version, name) VALUES ($1, $2)", m.version, m.name);
      result.applied.push_back(m.name);
    }
    tx.commit();
  } catch (const DatabaseError&) {
    throw;
  } catch (const std::exception& e) {
    throw DatabaseError(std::string("migrating the database failed, nothing was changed: ") + e.what());
  }
  result.version_after = std::max(result.version_before, newest);
  return result;
}

}  // namespace dtmf::store
