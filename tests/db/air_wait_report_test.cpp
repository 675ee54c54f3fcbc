// Database: waits for the air (migration 014). Each attempt keeps how long it waited before its
// chord; the report counts the frames that waited (a frame's retransmissions together), all
// their waits, and the longest any one command waited, its frames together, for the room and
// for each robot (a joint renewal counts for the robots it names); rows from before 014, whose
// wait is NULL, count as none.
#include <gtest/gtest.h>

#include "run_reader.h"
#include "store.h"
#include "temp_database.h"

using namespace dtmf::store;
using dtmf::test_support::TempDatabase;
using std::chrono::milliseconds;

namespace {

struct AirRun {
  TestRunRow run;
  WallTime t0 = WallClock::now() - std::chrono::hours(1);
  int slot = 0;

  CommandRow command(const std::string& robot, int address, const std::string& kind = "drive_for_duration") {
    CommandRow c;
    c.run_id = run.id;
    c.kind = kind;
    c.profile = "fast";
    c.requested_at = t0 + milliseconds(slot++ * 10'000);
    c.outcome = "confirmed";
    if (!robot.empty()) {
      c.robot = robot;
      c.robot_address = address;
    }
    c.host = "sender-a";
    return c;
  }

  // An attempt of `c`'s frame `position` that waited `wait_ms` for the air (none: a row from
  // before migration 014).
  FrameAttemptRow attempt(const CommandRow& c, int position, int number, std::optional<double> wait_ms) {
    FrameAttemptRow a;
    a.run_id = run.id;
    a.command_id = c.id;
    a.position = position;
    a.attempt = number;
    a.frame = std::to_string(100000 + slot * 8 + position * 2 + number);
    a.frame_width = 50;
    a.tones_hz = {1000.0};
    a.chord_started_at = c.requested_at + milliseconds(position * 1000 + number * 100);
    a.answer = "none";
    a.air_wait_ms = wait_ms;
    if (wait_ms && *wait_ms > 0) a.air_wait_reason = "sound 14 dB over the room's floor";
    return a;
  }
};

}  // namespace

TEST(AirWaitReport, FramesThatWaitedForTheAirAndHowLongAreCountedForTheRoomAndEachRobot) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/air-wait-report-" + std::to_string(::getpid()) + ".spill";
  AirRun r;
  r.run.label = "jammed";
  r.run.profile = "fast";
  r.run.started_at = r.t0 - milliseconds(100);
  {
    Store store(options);
    store.write(r.run);
    // alpha: held to the bound, then its retransmission at once; and one that never waited.
    const CommandRow held = r.command("alpha", 1);
    store.write(held);
    store.write(r.attempt(held, 0, 1, 8700));
    store.write(r.attempt(held, 0, 2, 0));
    const CommandRow at_once = r.command("alpha", 1);
    store.write(at_once);
    store.write(r.attempt(at_once, 0, 1, 0));
    // beta: a command of two frames, each of which waited; and a row from before 014.
    CommandRow two = r.command("beta", 2);
    two.frame_count = 2;
    store.write(two);
    store.write(r.attempt(two, 0, 1, 300));
    store.write(r.attempt(two, 1, 1, 200));
    const CommandRow old = r.command("beta", 2);
    store.write(old);
    store.write(r.attempt(old, 0, 1, std::nullopt));
    // A joint renewal of both, which waited; a stop for every robot, which never does.
    CommandRow renewal = r.command("", 0, "renewal");
    renewal.outcome = "sent";
    renewal.parameters = {{"robots", {"alpha", "beta"}}, {"addresses", {1, 2}}};
    store.write(renewal);
    store.write(r.attempt(renewal, 0, 1, 150));
    CommandRow every = r.command("", 0, "stop");
    every.every_robot = true;
    every.outcome = "sent";
    store.write(every);
    store.write(r.attempt(every, 0, 1, 0));
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }

  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const auto report = [&](const std::string& robot) {
    return tx.exec("SELECT * FROM run_report('" + r.run.id + "'::uuid" + (robot.empty() ? "" : ", '" + robot + "'") +
                   ")")[0];
  };
  const pqxx::row room = report("");
  EXPECT_EQ(room["air_waits"].as<int>(), 4) << "held's frame, both of two's, the renewal's";
  EXPECT_DOUBLE_EQ(room["air_wait_total_ms"].as<double>(), 8700 + 300 + 200 + 150);
  EXPECT_DOUBLE_EQ(room["air_wait_max_ms"].as<double>(), 8700);
  const pqxx::row alpha = report("alpha");
  EXPECT_EQ(alpha["air_waits"].as<int>(), 2);
  EXPECT_DOUBLE_EQ(alpha["air_wait_total_ms"].as<double>(), 8700 + 150);
  EXPECT_DOUBLE_EQ(alpha["air_wait_max_ms"].as<double>(), 8700);
  const pqxx::row beta = report("beta");
  EXPECT_EQ(beta["air_waits"].as<int>(), 3);
  EXPECT_DOUBLE_EQ(beta["air_wait_total_ms"].as<double>(), 300 + 200 + 150);
  EXPECT_DOUBLE_EQ(beta["air_wait_max_ms"].as<double>(), 300 + 200) << "a command's frames together";
  EXPECT_EQ(room["transmissions_sent"].as<int>(), 5) << "the other figures as before 014";
  EXPECT_EQ(tx.exec("SELECT count(*) FROM frame_attempts WHERE air_wait_reason IS NOT NULL")[0][0].as<int>(), 4);
  tx.commit();

  const RunReader reader(db.url());
  const auto read = reader.report(r.run.id, false);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->air_waits, 4);
  EXPECT_DOUBLE_EQ(read->air_wait_total_ms, 9350);
  ASSERT_TRUE(read->air_wait_max_ms);
  EXPECT_DOUBLE_EQ(*read->air_wait_max_ms, 8700);
}

TEST(AirWaitReport, ARunWhereNothingWaitedHasNoLongestWait) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/air-wait-none-" + std::to_string(::getpid()) + ".spill";
  AirRun r;
  r.run.label = "quiet";
  r.run.profile = "fast";
  r.run.started_at = r.t0 - milliseconds(100);
  {
    Store store(options);
    store.write(r.run);
    const CommandRow c = r.command("alpha", 1);
    store.write(c);
    store.write(r.attempt(c, 0, 1, 0));
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  const RunReader reader(db.url());
  const auto read = reader.report(r.run.id, false);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->air_waits, 0);
  EXPECT_DOUBLE_EQ(read->air_wait_total_ms, 0);
  EXPECT_FALSE(read->air_wait_max_ms);
}
