// Store library: reaching the database and bringing its schema up to date.
//
// The database is named by a libpq connection string or URL (`--db URL`); when none is
// given, libpq's own environment (PGHOST, PGPORT, PGUSER, PGDATABASE, PGPASSWORD, ...)
// decides. `--db none` (or an empty string) means no database at all.
//
// Migrations are the numbered files of db/migrations/, compiled into the programs. They are
// applied in one transaction under an advisory lock (two programs starting at once apply
// them once) and recorded in schema_migrations; applying again changes nothing; a database
// whose schema is newer than this build knows is refused.
#pragma once

#include <memory>
#include <optional>
#include <pqxx/connection>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace dtmf::store {

// The database cannot be used; what() says why and what to do.
class DatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// nullopt: use the libpq environment; "": no database.
using DatabaseUrl = std::optional<std::string>;

// Reads a --db flag value: "none" and "" mean no database; an absent flag means the
// libpq environment.
DatabaseUrl parse_database_flag(const std::optional<std::string>& flag);
bool database_disabled(const DatabaseUrl& url);
// What to tell people: the URL without its password, or "the libpq environment (PGHOST=...)".
std::string describe_database(const DatabaseUrl& url);

// Opens a connection, failing within a few seconds if the server does not answer.
// Throws DatabaseError.
std::unique_ptr<pqxx::connection> connect(const DatabaseUrl& url);

struct Migration {
  int version;
  std::string name;
  std::string_view sql;
};

// The migrations this build carries, in order (from db/migrations/NNN_name.sql).
const std::vector<Migration>& known_migrations();

struct MigrationResult {
  int version_before;
  int version_after;
  std::vector<std::string> applied;  // names, in order
};

// Brings the schema to the newest known version. Throws DatabaseError (schema newer than
// this build, or a migration failed).
MigrationResult migrate(pqxx::connection& connection);

// The schema version recorded in the database (0 for a database never migrated).
int schema_version(pqxx::connection& connection);

}  // namespace dtmf::store
