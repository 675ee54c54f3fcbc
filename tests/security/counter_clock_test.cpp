// Counters ahead of the clock (security/counter_clock.h): a freshness window needs both ends.
// Before this bound, one stop for every robot with a counter far in the future (a sender
// whose clock ran a day fast, or a holder of the room key who wrote "reserved 68719470000")
// was taken and kept, and every real stop after it was refused as old, for good. Now a robot
// takes no counter more than kClockMargin ahead of its clock, a window poisoned before the
// bound re-anchors to the clock by itself, and a sender refuses to start from such a counter.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "security/counter_file.h"
#include "security/room_freshness.h"
#include "support/temp_dir.h"

using namespace dtmf::security;
using std::chrono::hours;

namespace {

const auto kToday = std::chrono::system_clock::time_point{} + std::chrono::seconds(1796083200);  // 2026-12-01
const std::uint64_t kTodayCounter = clock_counter_floor(kToday);
constexpr std::uint64_t kPlanted = 68719470000;  // just under 2^36: what the attacker wrote

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

}  // namespace

TEST(CounterClock, TheMarginIsTenMinutesOfCountersAndBelowTheRoomsHour) {
  EXPECT_EQ(kClockMargin, 600u * kCountersPerSecond);
  EXPECT_LT(kClockMargin, kRoomWindow) << "a fast clock within the margin must not push the window past a true one";
  EXPECT_FALSE(ahead_of_clock(kTodayCounter + kClockMargin, kToday));
  EXPECT_TRUE(ahead_of_clock(kTodayCounter + kClockMargin + 1, kToday));
  EXPECT_DOUBLE_EQ(seconds_ahead_of_clock(clock_counter_floor(kToday + hours(24)), kToday), 86400.0);
  EXPECT_DOUBLE_EQ(seconds_ahead_of_clock(clock_counter_floor(kToday - hours(24)), kToday), -86400.0);
}

TEST(CounterClock, AStopFromAClockADayFastIsNeitherTakenNorKeptAndTheNextTrueStopIsNew) {
  RoomFreshness room(0);
  const std::uint64_t day_fast = clock_counter_floor(kToday + hours(24));
  EXPECT_EQ(room.check(day_fast, kTodayCounter), Freshness::Ahead);
  EXPECT_EQ(room.check(kPlanted, kTodayCounter), Freshness::Ahead);
  EXPECT_EQ(room.newest(), 0u) << "nothing was taken";
  EXPECT_EQ(room.check(kTodayCounter + 20, kTodayCounter), Freshness::New) << "a second later, a true stop";
}

TEST(CounterClock, AStopFromAClockADaySlowIsNewWhileNoNewerWasTaken) {
  RoomFreshness room(0);
  const std::uint64_t day_slow = clock_counter_floor(kToday - hours(24));
  ASSERT_EQ(room.check(day_slow, kTodayCounter), Freshness::New);
  room.take(day_slow);
  EXPECT_EQ(room.check(kTodayCounter, kTodayCounter), Freshness::New) << "the true sender after it";
  room.take(kTodayCounter);
  EXPECT_EQ(room.check(day_slow + 20, kTodayCounter), Freshness::Stale)
      << "a day behind the newest: refused as the hour's window says (docs/security.md)";
}

TEST(CounterClock, AWindowPoisonedBeforeTheBoundReanchorsToTheClock) {
  RoomFreshness room(kPlanted);  // what the robot kept before this bound
  EXPECT_EQ(room.check(kTodayCounter, kTodayCounter), Freshness::Stale) << "before re-anchoring, a true stop looks old";
  const auto kept = room.reanchor(kTodayCounter);
  ASSERT_TRUE(kept);
  EXPECT_EQ(*kept, kTodayCounter - kRoomWindow) << "as if the newest had been taken an hour ago";
  EXPECT_EQ(room.check(kTodayCounter, kTodayCounter), Freshness::New);
  EXPECT_EQ(room.check(kTodayCounter - kRoomWindow / 2, kTodayCounter), Freshness::New) << "a clock half an hour slow";
  EXPECT_EQ(room.check(kTodayCounter - kRoomWindow, kTodayCounter), Freshness::Stale);
  EXPECT_FALSE(room.reanchor(kTodayCounter)) << "once is enough";
  EXPECT_FALSE(RoomFreshness(kTodayCounter + kClockMargin).reanchor(kTodayCounter)) << "within the margin: kept";
}

TEST(CounterClock, AStopTakenBeforeTheRobotsClockWasSetBackIsStillARepeat) {
  RoomFreshness room(0);
  const std::uint64_t earlier = kTodayCounter - 2 * kClockMargin;
  room.take(earlier);
  room.take(kTodayCounter);
  const std::uint64_t set_back = kTodayCounter - 3 * kClockMargin / 2;  // NTP corrected a clock 15 min fast
  ASSERT_TRUE(room.reanchor(set_back));
  EXPECT_EQ(room.check(earlier, set_back), Freshness::Repeat) << "played again: taken already";
  EXPECT_EQ(room.check(kTodayCounter, set_back), Freshness::Ahead) << "past the clock now: stops, not kept";
  EXPECT_EQ(room.check(set_back + 1, set_back), Freshness::New);
}

TEST(CounterClock, ARobotsPoisonedRoomStateIsRewrittenWhenTheWindowReanchors) {
  dtmf::test_support::TempDir dir("dtmf-clock-state");
  const auto key = LinkKey::generate();
  {
    const auto robot = FileCounterStore::open_robot(dir.path, *key, RobotKey::Room);
    robot->accept(kPlanted);
    EXPECT_FALSE(robot->stored_counter()) << "no state yet: nothing found";
  }
  const auto robot = FileCounterStore::open_robot(dir.path, *key, RobotKey::Room);
  EXPECT_EQ(robot->stored_counter(), kPlanted) << "found as kept, for the start's warning";
  RoomFreshness room(robot->last_accepted());
  robot->reanchor(*room.reanchor(kTodayCounter));
  EXPECT_EQ(robot->last_accepted(), kTodayCounter - kRoomWindow);
  robot->accept(kTodayCounter);
  EXPECT_EQ(robot->last_accepted(), kTodayCounter) << "kept again from then on";
}

TEST(CounterClock, ASenderRefusesToStartFromACounterFarAheadOfItsClock) {
  dtmf::test_support::TempDir dir("dtmf-clock-state");
  const auto key = LinkKey::generate();
  std::filesystem::create_directories(dir.path);
  std::filesystem::permissions(dir.path, std::filesystem::perms::owner_all);
  write(dir.path / ("sender-" + key->id_hex()), "reserved " + std::to_string(kPlanted) + "\n");
  for (const CounterPace pace : {CounterPace::Frames, CounterPace::Clock}) {
    try {
      FileCounterStore::open_sender(
          dir.path, *key, [] { return kToday; }, pace);
      ADD_FAILURE() << "a planted counter was taken";
    } catch (const std::runtime_error& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find("holds counter 68719470000"), std::string::npos) << what;
      EXPECT_NE(what.find("ahead of this machine's clock"), std::string::npos) << what;
      EXPECT_NE(what.find("remove the file"), std::string::npos) << what;
      EXPECT_NE(what.find("set it"), std::string::npos) << what;
    }
  }
  const std::uint64_t near = kTodayCounter + kClockMargin;  // a clock a little fast: within the margin
  write(dir.path / ("sender-" + key->id_hex()), "reserved " + std::to_string(near) + "\n");
  const auto sender = FileCounterStore::open_sender(dir.path, *key, [] { return kToday; });
  EXPECT_EQ(sender->stored_counter(), near);
  EXPECT_EQ(sender->next_counter(), near);
}
