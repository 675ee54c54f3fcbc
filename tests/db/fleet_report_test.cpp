// Database: one run of a sender driving two robots (migrations 010, 011, 012). run_report(run)
// covers the whole room, run_report(run, robot) one robot; a stop for every robot and a joint
// renewal are counted apart (no robot answers them), and so are a renewal's receptions that
// renewed nothing; a robot of another sender in the same room, at another address, is
// no false positive of this run; RunReader and the runs view name the run's robots.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <iterator>

#include "run_reader.h"
#include "store.h"
#include "temp_database.h"

using namespace dtmf::store;
using dtmf::test_support::TempDatabase;
using std::chrono::milliseconds;

namespace {

constexpr int kSlotMs = 400;

struct FleetRun {
  TestRunRow run;
  WallTime t0 = WallClock::now() - std::chrono::hours(1);
  int slot = 0;

  // A command of one frame to `robot` at `address`, its ACK heard; heard by the robot unless
  // `dropped`. Returns the frame's start.
  void command(Store& store, const std::string& robot, int address, bool dropped) {
    CommandRow c;
    c.run_id = run.id;
    c.kind = "drive_for_duration";
    c.profile = "fast";
    c.requested_at = t0 + milliseconds(slot * kSlotMs);
    c.outcome = "confirmed";
    c.robot = robot;
    c.robot_address = address;
    c.host = "sender-a";
    store.write(c);
    const WallTime start = c.requested_at;
    store.write(attempt(c.id, 0, start, "ack"));
    if (!dropped) store.write(reception(robot, address, start + milliseconds(120), "drive_for_duration"));
    ++slot;
  }

  // A stop for every robot: two copies, no answer, each executed by both robots.
  void stop_every_robot(Store& store) {
    CommandRow c;
    c.run_id = run.id;
    c.kind = "stop";
    c.profile = "fast";
    c.frame_count = 2;
    c.requested_at = t0 + milliseconds(slot * kSlotMs);
    c.outcome = "sent";
    c.every_robot = true;
    c.host = "sender-a";
    store.write(c);
    for (int copy = 0; copy < 2; ++copy) {
      const WallTime start = c.requested_at + milliseconds(copy * 110);
      FrameAttemptRow a = attempt(c.id, copy, start, "");
      a.answer.reset();
      store.write(a);
      store.write(reception("alpha", 1, start + milliseconds(80), "stop every_robot", a.frame));
      store.write(reception("beta", 2, start + milliseconds(81), "stop every_robot", a.frame));
    }
    ++slot;
  }

  // A joint renewal of alpha and beta (migration 011): no answer, taken by both.
  // A joint renewal of alpha and beta's row, ending `outcome`.
  CommandRow renewal_row(const std::string& outcome) const {
    CommandRow c;
    c.run_id = run.id;
    c.kind = "renewal";
    c.profile = "fast";
    c.requested_at = t0 + milliseconds(slot * kSlotMs);
    c.outcome = outcome;
    c.parameters = {{"robots", {"alpha", "beta"}}, {"addresses", {1, 2}}};
    c.host = "sender-a";
    return c;
  }

  void renewal(Store& store) {
    const CommandRow c = renewal_row("sent");
    store.write(c);
    FrameAttemptRow a = attempt(c.id, 0, c.requested_at, "");
    a.answer.reset();
    store.write(a);
    for (const auto& [robot, address] : {std::pair{"alpha", 1}, std::pair{"beta", 2}}) {
      ReceptionRow r = reception(robot, address, c.requested_at + milliseconds(150), "velocity", a.frame);
      r.event = "renewal";
      r.reply.reset();
      store.write(r);
    }
    ++slot;
    last_renewal_frame = a.frame;
  }

  // A renewal cancelled while it waited for the air, a stream it renewed having ended
  // (migration 013): its row, and no frame attempt.
  void renewal_cancelled(Store& store) { store.write(renewal_row("cancelled")); }

  // The last renewal heard again by a robot that renews nothing with it (migration 012): its
  // echo ('repeat'), or a plain renewal of a velocity the robot no longer holds ('ignored').
  void renewal_not_taken(Store& store, const std::string& robot, int address, const std::string& event) {
    ReceptionRow r = reception(robot, address, t0 + milliseconds((slot - 1) * kSlotMs + 300), "", last_renewal_frame);
    r.event = event;
    r.command.clear();
    r.reply.reset();
    store.write(r);
  }
  std::string last_renewal_frame;

  FrameAttemptRow attempt(const std::string& command_id, int position, WallTime start, const std::string& answer) {
    FrameAttemptRow a;
    a.run_id = run.id;
    a.command_id = command_id;
    a.position = position;
    a.frame = std::to_string(100000 + slot * 4 + position);
    a.frame_width = 50;
    a.tones_hz = {1000.0};
    a.chord_started_at = start;
    a.chord_ended_at = start + milliseconds(102);
    if (!answer.empty()) {
      a.answer = answer;
      a.answered_at = start + milliseconds(150);
    }
    return a;
  }

  ReceptionRow reception(const std::string& robot, int address, WallTime heard, const std::string& command,
                         std::string frame = "") {
    ReceptionRow r;
    r.host = robot;
    r.robot_address = address;
    r.profile = "fast";
    r.heard_at = heard;
    r.frame = frame.empty() ? std::to_string(100000 + slot * 4) : frame;
    r.frame_width = 50;
    r.crc_ok = true;
    r.event = "command";
    r.command = command;
    if (command != "stop every_robot") r.reply = "ack";
    return r;
  }
};

// The store's options for `db`, with a spill file of the test's own.
StoreOptions store_options(const TempDatabase& db, const std::string& test) {
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/" + test + "-" + std::to_string(::getpid()) + ".spill";
  return options;
}

// A run of sender-a's whose first command starts at f.t0.
FleetRun fleet_run() {
  FleetRun f;
  f.run.label = "fleet";
  f.run.profile = "fast";
  f.run.started_at = f.t0 - milliseconds(100);
  return f;
}

}  // namespace

TEST(FleetReport, TheRoomAndEachRobotAddUpAndStopsForEveryRobotStandApart) {
  TempDatabase db;
  const StoreOptions options = store_options(db, "fleet-report");
  FleetRun f = fleet_run();
  f.run.ended_at = f.t0 + milliseconds(20 * kSlotMs);
  {
    Store store(options);
    store.write(f.run);
    for (int i = 0; i < 4; ++i) f.command(store, "alpha", 1, false);
    for (int i = 0; i < 3; ++i) f.command(store, "beta", 2, i == 1);  // beta missed one frame
    f.stop_every_robot(store);
    f.renewal(store);
    f.renewal(store);
    f.renewal_cancelled(store);
    f.renewal_not_taken(store, "alpha", 1, "repeat");
    f.renewal_not_taken(store, "beta", 2, "ignored");
    // Another sender's robot in the same room took its own frame meanwhile: not this run's.
    store.write(f.reception("gamma", 5, f.t0 + milliseconds(3 * kSlotMs + 50), "turn", "777777"));
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }

  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const auto report = [&](const std::string& robot) {
    return tx.exec("SELECT * FROM run_report('" + f.run.id + "'::uuid" + (robot.empty() ? "" : ", '" + robot + "'") +
                   ")")[0];
  };
  const pqxx::row room = report("");
  EXPECT_TRUE(room["robot"].is_null());
  EXPECT_EQ(room["transmissions_sent"].as<int>(), 7) << "the stop's copies are no transmissions";
  EXPECT_EQ(room["transmissions_received"].as<int>(), 6) << "gamma's and the stop's receptions left out";
  EXPECT_EQ(room["successfully_matched"].as<int>(), 6);
  EXPECT_EQ(room["dropped"].as<int>(), 1);
  EXPECT_EQ(room["false_positives"].as<int>(), 0) << "another sender's robot is no false positive";
  EXPECT_EQ(room["sender_confirmed"].as<int>(), 7);
  EXPECT_EQ(room["every_robot_stops_sent"].as<int>(), 1);
  EXPECT_EQ(room["every_robot_stops_executed"].as<int>(), 4) << "two copies, each executed by both robots";
  EXPECT_EQ(room["renewals_sent"].as<int>(), 2)
      << "joint renewals are no transmissions either, and the cancelled one never went on air";
  EXPECT_EQ(room["renewals_executed"].as<int>(), 4) << "two renewals, each taken by both robots";
  EXPECT_EQ(room["renewals_not_taken"].as<int>(), 2) << "an echo, and a renewal of a velocity no longer held";

  const pqxx::row alpha = report("alpha"), beta = report("beta");
  EXPECT_EQ(alpha["robot"].as<std::string>(), "alpha");
  EXPECT_EQ(alpha["transmissions_sent"].as<int>(), 4);
  EXPECT_EQ(alpha["successfully_matched"].as<int>(), 4);
  EXPECT_EQ(alpha["every_robot_stops_executed"].as<int>(), 2);
  EXPECT_EQ(alpha["renewals_sent"].as<int>(), 2) << "both renewals named alpha";
  EXPECT_EQ(alpha["renewals_executed"].as<int>(), 2);
  EXPECT_EQ(beta["transmissions_sent"].as<int>(), 3);
  EXPECT_EQ(beta["successfully_matched"].as<int>(), 2);
  EXPECT_EQ(beta["dropped"].as<int>(), 1);
  EXPECT_EQ(beta["false_positives"].as<int>(), 0) << "a renewal beta renewed nothing with is no false positive";
  EXPECT_EQ(alpha["false_positives"].as<int>(), 0);
  EXPECT_EQ(alpha["renewals_not_taken"].as<int>(), 1);
  // The robots add up to the room.
  for (const char* column :
       {"transmissions_sent", "transmissions_received", "successfully_matched", "dropped", "sender_confirmed",
        "every_robot_stops_executed", "renewals_executed", "renewals_not_taken"}) {
    EXPECT_EQ(alpha[column].as<int>() + beta[column].as<int>(), room[column].as<int>()) << column;
  }
  EXPECT_EQ(report("gamma")["transmissions_sent"].as<int>(), 0) << "no command of this run named gamma";
  const pqxx::row listed =
      tx.exec("SELECT robots::text, transmissions_sent FROM runs WHERE id = '" + f.run.id + "'")[0];
  EXPECT_EQ(listed[0].as<std::string>(), "{alpha,beta}");
  EXPECT_EQ(listed[1].as<int>(), 7);

  const RunReader reader(db.url());
  const auto read = reader.report(f.run.id, true, std::string("beta"));
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->run.robots, (std::vector<std::string>{"alpha", "beta"}));
  EXPECT_EQ(read->robot, "beta");
  EXPECT_EQ(read->transmissions_sent, 3);
  EXPECT_EQ(read->frames.size(), 3u) << "beta's frames only";
  EXPECT_EQ(reader.report(f.run.id, false)->every_robot_stops_sent, 1);
  EXPECT_EQ(reader.report(f.run.id, false)->renewals_sent, 2);
  EXPECT_EQ(read->renewals_executed, 2);
}

// bench/e2e/fleet_executions.sql, which fleet_load.sh runs: every frame a robot executed is
// one a sender sent to its address (or to every robot); another robot's frame executed, and
// a frame no sender sent, are each counted.
TEST(FleetReport, ExecutionsByTheWrongRobotAndOfUnsentFramesAreCounted) {
  TempDatabase db;
  const StoreOptions options = store_options(db, "fleet-executions");
  FleetRun f = fleet_run();
  std::ifstream file(std::string(DTMF_SOURCE_DIR) + "/bench/e2e/fleet_executions.sql");
  ASSERT_TRUE(file.good());
  const std::string executions((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto count = [&] {
    pqxx::connection c(db.url());
    pqxx::work tx(c);
    const pqxx::row row = tx.exec(executions)[0];
    return std::array{row[0].as<int>(), row[1].as<int>(), row[2].as<int>()};
  };
  {
    Store store(options);
    store.write(f.run);
    for (int i = 0; i < 3; ++i) f.command(store, "alpha", 1, false);
    f.command(store, "beta", 2, false);
    f.stop_every_robot(store);  // executed by both: sent to every robot
    f.renewal(store);           // taken, not executed
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  EXPECT_EQ(count(), (std::array{8, 0, 0})) << "4 commands and 2 stop copies executed by both robots";
  {
    Store store(options);
    // beta executes alpha's first frame, heard while it sounded; then a frame no one sent.
    store.write(f.reception("beta", 2, f.t0 + milliseconds(60), "drive_for_duration", "100000"));
    store.write(f.reception("alpha", 1, f.t0 + milliseconds(70), "drive_for_duration", "424242"));
    // alpha's own first frame heard 10 s late is no longer that frame.
    store.write(f.reception("alpha", 1, f.t0 + milliseconds(10000), "drive_for_duration", "100000"));
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  EXPECT_EQ(count(), (std::array{11, 1, 2}));
}
