// dtmf-migrate: brings a database's schema up to date (the programs also do it at start-up).
//
//   dtmf-migrate --db postgresql://postgres@127.0.0.1:25432/postgres
//   dtmf-migrate --status            (libpq environment: PGHOST, PGDATABASE, ...)
// Exit codes: 0 done, 1 the database refused or could not be reached, 2 bad usage.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <pqxx/pqxx>

#include "database.h"
#include "program_main.h"

int main(int argc, char** argv) {
  CLI::App app{"dtmf-migrate: apply db/migrations to the dtmf-teleop database"};
  std::optional<std::string> db;
  bool status_only = false;
  app.add_option("--db", db,
                 "PostgreSQL URL or connection string; default: the libpq environment (PGHOST, ...); also DTMF_DB_URL")
      ->envname("DTMF_DB_URL");
  app.add_flag("--status", status_only, "only print the schema version, change nothing");
  app.footer("Exit codes: 0 done, 1 the database refused or could not be reached, 2 bad usage.");
  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  using namespace dtmf::store;
  const DatabaseUrl url = parse_database_flag(db);
  if (database_disabled(url)) {
    std::fprintf(stderr, "dtmf-migrate: --db none: there is no database to migrate\n");
    return dtmf::program::kExitUsage;
  }
  return dtmf::program::run(
      [&] {
        auto connection = connect(url);
        const int newest = known_migrations().empty() ? 0 : known_migrations().back().version;
        if (status_only) {
          std::printf("%s: schema version %d; this build knows up to %d\n", describe_database(url).c_str(),
                      schema_version(*connection), newest);
          return 0;
        }
        const MigrationResult result = migrate(*connection);
        for (const auto& name : result.applied) std::printf("applied %s\n", name.c_str());
        std::printf("%s: schema version %d (was %d)\n", describe_database(url).c_str(), result.version_after,
                    result.version_before);
        return 0;
      },
      [](const std::string& error) { std::fprintf(stderr, "dtmf-migrate: %s\n", error.c_str()); });
}
