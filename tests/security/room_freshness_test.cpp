// The room key's freshness (security/room_freshness.h) and its counters on disk: senders
// count from their clocks, so their stops reach a robot out of order, and a robot takes each
// once within an hour's window; a stop played again is never taken twice; after a restart
// nothing at or below the newest counter on disk is taken; a robot with no state for the room
// key starts at 0 by itself (RobotKey::Room), and a sender's room counters never fall behind
// its clock (CounterPace::Clock).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "security/counter_file.h"
#include "security/room_freshness.h"
#include "support/temp_dir.h"

using namespace dtmf::security;

namespace {
constexpr std::uint64_t kNow = 1'000'000;  // the robot's clock as a counter: every counter below lies within it
}  // namespace

TEST(RoomFreshness, TwoSendersStopsTakenOnceEachInEitherOrder) {
  RoomFreshness room(0);
  const std::uint64_t ahead = 1'000'000, behind = ahead - 20 * 30;  // a clock 30 s behind
  ASSERT_EQ(room.check(ahead, kNow), Freshness::New);
  room.take(ahead);
  EXPECT_EQ(room.check(behind, kNow), Freshness::New) << "a sender 30 s behind must still stop the robot";
  room.take(behind);
  EXPECT_EQ(room.check(behind, kNow), Freshness::Repeat) << "the same stop played again";
  EXPECT_EQ(room.check(ahead, kNow), Freshness::Repeat);
  EXPECT_EQ(room.check(ahead + 1, kNow), Freshness::New);
  EXPECT_EQ(room.newest(), ahead);
}

TEST(RoomFreshness, OlderThanTheWindowIsStale) {
  RoomFreshness room(0);
  const std::uint64_t newest = 10 * kRoomWindow;
  room.take(newest);
  EXPECT_EQ(room.check(newest - kRoomWindow, kNow), Freshness::Stale) << "an hour old: a recording";
  EXPECT_EQ(room.check(newest - kRoomWindow + 1, kNow), Freshness::New);
  EXPECT_EQ(room.check(0, kNow), Freshness::Stale);
}

TEST(RoomFreshness, AfterARestartNothingAtOrBelowTheNewestOnDiskIsTaken) {
  RoomFreshness room(5000);  // what the store kept
  EXPECT_EQ(room.check(5000, kNow), Freshness::Stale);
  EXPECT_EQ(room.check(4999, kNow), Freshness::Stale) << "whether it was taken before the restart is not known";
  EXPECT_EQ(room.check(5001, kNow), Freshness::New);
}

TEST(RoomFreshness, ForgettingTheOldestClosesTheWindowAtIt) {
  RoomFreshness room(0);
  const std::uint64_t first = 100'000;
  for (std::uint64_t i = 0; i <= kRoomRemembered; ++i) room.take(first + 2 * i);  // one more than remembered
  EXPECT_EQ(room.check(first, kNow), Freshness::Stale) << "forgotten, so no longer known to be new";
  EXPECT_EQ(room.check(first - 1, kNow), Freshness::Stale) << "below the forgotten one";
  EXPECT_EQ(room.check(first + 1, kNow), Freshness::New) << "above it, never taken";
  EXPECT_EQ(room.check(first + 3, kNow), Freshness::New) << "between remembered ones, never taken";
  EXPECT_EQ(room.check(first + 2, kNow), Freshness::Repeat);
}

TEST(RoomCounters, ARobotWithNoRoomStateStartsAtZeroAndKeepsTheNewest) {
  dtmf::test_support::TempDir dir("dtmf-room-state");
  const auto key = LinkKey::generate();
  {
    const auto robot = FileCounterStore::open_robot(dir.path / "state", *key, RobotKey::Room);
    EXPECT_EQ(robot->last_accepted(), 0u);
    robot->accept(700);
    robot->accept(650);  // an earlier sender's, in the window: the newest stays
  }
  EXPECT_EQ(FileCounterStore::open_robot(dir.path / "state", *key, RobotKey::Room)->last_accepted(), 700u);
  EXPECT_THROW(FileCounterStore::open_robot(dir.path / "other", *key), std::runtime_error)
      << "a robot's own key still needs its state";
}

TEST(RoomCounters, ASendersRoomCountersFollowItsClock) {
  dtmf::test_support::TempDir dir("dtmf-room-state");
  const auto key = LinkKey::generate();
  auto now = std::chrono::system_clock::now();
  const auto clock = [&] { return now; };
  const auto paced = FileCounterStore::open_sender(dir.path / "a", *key, clock, CounterPace::Clock);
  const auto framed = FileCounterStore::open_sender(dir.path / "b", *key, clock, CounterPace::Frames);
  const std::uint64_t first = paced->next_counter();
  EXPECT_EQ(framed->next_counter(), first);
  now += std::chrono::hours(24);  // a day of no stops
  EXPECT_EQ(paced->next_counter(), clock_counter_floor(now)) << "a day later, the clock's counter";
  EXPECT_EQ(framed->next_counter(), first + 1) << "a key's own counters just go on";
  EXPECT_EQ(paced->next_counter(), clock_counter_floor(now) + 1) << "never the same twice within a tick";
}
