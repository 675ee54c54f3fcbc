// Database: migrations from nothing, again, concurrently, and against a newer schema.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "database.h"
#include "temp_database.h"

using namespace dtmf::store;
using dtmf::test_support::TempDatabase;

namespace {
int newest() { return known_migrations().back().version; }
}  // namespace

TEST(Migrations, AreNumberedFromOneWithoutGaps) {
  const auto& all = known_migrations();
  ASSERT_GE(all.size(), 3u);
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].version, static_cast<int>(i + 1));
    EXPECT_FALSE(all[i].sql.empty());
  }
  EXPECT_EQ(all[0].name, "001_schema");
}

TEST(Migrations, BuildTheSchemaFromAnEmptyDatabase) {
  TempDatabase db;
  auto c = connect(db.url());
  EXPECT_EQ(schema_version(*c), 0);
  const MigrationResult result = migrate(*c);
  EXPECT_EQ(result.version_before, 0);
  EXPECT_EQ(result.version_after, newest());
  EXPECT_EQ(result.applied.size(), known_migrations().size());
  EXPECT_EQ(schema_version(*c), newest());
  for (const char* table : {"test_runs", "commands", "frame_attempts", "receptions", "schema_migrations"}) {
    EXPECT_TRUE(db.query<bool>(std::string("SELECT to_regclass('") + table + "') IS NOT NULL")) << table;
  }
  EXPECT_TRUE(
      db.query<bool>("SELECT to_regprocedure('run_report(uuid,double precision,double precision)') IS NOT NULL"));
  EXPECT_TRUE(db.query<bool>("SELECT to_regprocedure('store_rows(jsonb)') IS NOT NULL"));
  EXPECT_TRUE(
      db.query<bool>("SELECT to_regprocedure('run_frames(bigint,double precision,double precision)') IS NOT NULL"));
  EXPECT_EQ(db.query<std::string>("SELECT frame_bits(45789)"), "1011001011011101");
}

TEST(Migrations, ApplyingTwiceChangesNothing) {
  TempDatabase db;
  auto c = connect(db.url());
  migrate(*c);
  const auto objects = db.query<long>("SELECT count(*) FROM pg_class WHERE relnamespace = 'public'::regnamespace");
  const auto stamp = db.query<std::string>("SELECT max(applied_at)::text FROM schema_migrations");
  const MigrationResult again = migrate(*c);
  EXPECT_TRUE(again.applied.empty());
  EXPECT_EQ(again.version_before, newest());
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM pg_class WHERE relnamespace = 'public'::regnamespace"), objects);
  EXPECT_EQ(db.query<std::string>("SELECT max(applied_at)::text FROM schema_migrations"), stamp);
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM schema_migrations"), static_cast<long>(known_migrations().size()));
}

TEST(Migrations, TwoProgramsStartingAtOnceMigrateOnce) {
  TempDatabase db;
  std::vector<std::thread> threads;
  std::atomic<int> applied{0}, failures{0};
  for (int i = 0; i < 4; ++i) {
    threads.emplace_back([&] {
      try {
        auto c = connect(db.url());
        applied += static_cast<int>(migrate(*c).applied.size());
      } catch (...) {
        ++failures;
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(applied.load(), static_cast<int>(known_migrations().size()));
}

TEST(Migrations, ADatabaseNewerThanThisBuildIsRefusedAndLeftAlone) {
  TempDatabase db;
  auto c = connect(db.url());
  migrate(*c);
  {
    pqxx::work tx(*c);
    tx.exec("INSERT INTO schema_migrations (version, name) VALUES (999, '999_from_the_future')");
    tx.commit();
  }
  try {
    migrate(*c);
    FAIL() << "a newer schema was accepted";
  } catch (const DatabaseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("version 999"), std::string::npos) << what;
    EXPECT_NE(what.find("newer than this program knows"), std::string::npos) << what;
    EXPECT_NE(what.find("upgrade"), std::string::npos) << what;
  }
  EXPECT_EQ(schema_version(*c), 999);
}

TEST(Migrations, AnUnreachableDatabaseSaysWhatToDo) {
  try {
    connect(std::string("postgresql://postgres:secret@127.0.0.1:1/none"));
    FAIL();
  } catch (const DatabaseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot reach the database"), std::string::npos) << what;
    EXPECT_NE(what.find("--db none"), std::string::npos) << what;
    EXPECT_EQ(what.find("secret"), std::string::npos) << "the password leaked: " << what;
  }
}

TEST(Migrations, DatabaseFlagValues) {
  EXPECT_FALSE(parse_database_flag(std::nullopt).has_value());
  EXPECT_TRUE(database_disabled(parse_database_flag(std::string("none"))));
  EXPECT_TRUE(database_disabled(parse_database_flag(std::string(""))));
  EXPECT_FALSE(database_disabled(parse_database_flag(std::string("postgresql://x/y"))));
  EXPECT_EQ(describe_database(std::string("host=a password=hunter2 dbname=b")), "host=a password=*** dbname=b");
}

namespace {
int run(const std::string& command) {
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

TEST(MigrateCommand, MigratesReportsStatusAndFailsClearly) {
  TempDatabase db;
  EXPECT_EQ(run(std::string(DTMF_MIGRATE_PATH) + " --db " + db.url()), 0);
  EXPECT_EQ(db.query<int>("SELECT max(version) FROM schema_migrations"), newest());
  EXPECT_EQ(run(std::string(DTMF_MIGRATE_PATH) + " --status --db " + db.url()), 0);
  EXPECT_EQ(run(std::string(DTMF_MIGRATE_PATH) + " --db postgresql://postgres@127.0.0.1:1/x"), 1);
  EXPECT_EQ(run(std::string(DTMF_MIGRATE_PATH) + " --db none"), 2);
  EXPECT_EQ(run(std::string(DTMF_MIGRATE_PATH) + " --no-such-flag"), 2);
}

// run_report() is restated by several migrations (each kept as it shipped). The newest
// statement is the one live, there is one function per signature, and its columns are the
// ones docs/database.md defines.
namespace {

// The body between the $$ of the newest migration's `FUNCTION run_report(run uuid,` (the
// room's: its second parameter on the next line).
std::string newest_report_body() {
  const auto& all = known_migrations();
  for (auto m = all.rbegin(); m != all.rend(); ++m) {
    const auto at = m->sql.rfind("FUNCTION run_report(run uuid,\n");
    if (at == std::string::npos) continue;
    const auto open = m->sql.find("$$", at), close = m->sql.find("$$", open + 2);
    return std::string(m->sql.substr(open + 2, close - open - 2));
  }
  return {};
}

// The column names of docs/database.md's report table, braces expanded: `a_{x,y}_b`.
std::vector<std::string> documented_report_columns() {
  std::ifstream in(std::string(DTMF_SOURCE_DIR) + "/docs/database.md");
  std::vector<std::string> names;
  bool in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| column | definition", 0) == 0)
      in_table = true;
    else if (in_table && line.rfind("|", 0) != 0)
      break;
    if (!in_table || line.rfind("| `", 0) != 0) continue;
    const std::string cell = line.substr(2, line.find(" |", 2) - 2);
    for (std::size_t at = cell.find('`'); at != std::string::npos; at = cell.find('`', cell.find('`', at + 1) + 1)) {
      const std::string name = cell.substr(at + 1, cell.find('`', at + 1) - at - 1);
      const auto brace = name.find('{');
      if (brace == std::string::npos) {
        names.push_back(name);
        continue;
      }
      const auto end = name.find('}');
      std::istringstream parts(name.substr(brace + 1, end - brace - 1));
      for (std::string part; std::getline(parts, part, ',');)
        names.push_back(name.substr(0, brace) + part + name.substr(end + 1));
    }
  }
  return names;
}

}  // namespace

TEST(Migrations, TheNewestRunReportIsTheOneLiveAndDocumented) {
  TempDatabase db;
  auto c = connect(db.url());
  migrate(*c);
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM pg_proc WHERE proname = 'run_report'"), 4)
      << "by id and by number, each for the room and for one robot";
  const std::string body = newest_report_body();
  ASSERT_FALSE(body.empty());
  EXPECT_EQ(
      db.query<std::string>(
          "SELECT prosrc FROM pg_proc WHERE oid = 'run_report(uuid,double precision,double precision)'::regprocedure"),
      body)
      << "the live run_report(uuid) is not the newest migration's";

  const std::vector<std::string> documented = documented_report_columns();
  ASSERT_GE(documented.size(), 20u);
  const auto live = db.query<std::string>(
      "SELECT string_agg(attname, ',' ORDER BY attnum) FROM pg_attribute WHERE attrelid = "
      "(SELECT typrelid FROM pg_type WHERE typname = 'run_report_row') AND attnum > 0 AND NOT attisdropped");
  std::vector<std::string> columns;
  std::istringstream in(live);
  for (std::string name; std::getline(in, name, ',');) columns.push_back(name);
  // Which run it is comes first; the table defines the figures.
  const std::vector<std::string> identity = {"run_id", "run_number", "label", "profile", "started_at", "ended_at"};
  ASSERT_GT(columns.size(), identity.size());
  EXPECT_EQ(std::vector<std::string>(columns.begin(), columns.begin() + 6), identity);
  std::vector<std::string> figures(columns.begin() + 6, columns.end());
  std::vector<std::string> documented_sorted = documented;
  std::sort(figures.begin(), figures.end());
  std::sort(documented_sorted.begin(), documented_sorted.end());
  EXPECT_EQ(figures, documented_sorted) << "docs/database.md's report table and run_report_row differ";
}
