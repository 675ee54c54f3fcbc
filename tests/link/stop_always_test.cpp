// A stop always gets through (issue 59): whatever a clock, a planted counter or a lost
// synchronisation did, the next true Stop or stop for every robot stops the robot.
//   - One room stop whose counter lay far ahead (a sender whose clock ran a day fast, or a
//     holder of the room key who wrote "reserved 68719470000") was taken and kept, and every
//     true stop after it refused as old, for good. Now it still stops the robot, and is not
//     kept; a robot that kept one before re-anchors to its clock; a day-slow sender's stop
//     stops the robot too.
//   - A keyed Stop waited behind a synchronisation frame, and never went out when that was
//     not answered. Now a Stop carries its whole counter: one frame, placed by a robot that
//     never heard a synchronisation, answered with its tag.
//   - A command whose counter lies past the robot's clock is refused and not kept.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>

#include "command/command.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "security/counter_clock.h"
#include "security/counter_store.h"
#include "security/room_freshness.h"
#include "support/robot_ear.h"
#include "support/test_key.h"

using namespace dtmf;
using std::chrono::hours;
using test_support::test_key;

namespace {

const LinkProfile& p = profile_by_name("fast");
const auto kToday = std::chrono::system_clock::time_point{} + std::chrono::seconds(1796083200);  // 2026-12-01
const std::uint64_t kTodayCounter = security::clock_counter_floor(kToday);
constexpr std::uint64_t kPlanted = 68719470000;
const auto kRoomKey = test_key(0x77);

std::uint64_t counter_at(std::chrono::system_clock::time_point t) { return security::clock_counter_floor(t); }

// A sender's link under `key`, its counters from `first` (a clock's value, or a planted one).
std::unique_ptr<link::Link> sender(std::shared_ptr<const security::LinkKey> key, std::uint64_t first,
                                   std::uint8_t address = 0) {
  link::LinkOptions o;
  o.address = address;
  o.key = std::move(key);
  o.counters = std::make_shared<security::MemoryCounterStore>(first);
  return link::make_link(p, o);
}

// Robot 1: its own key, the room key, the room's newest counter kept as `room_kept`, and a
// clock that reads today.
struct Robot {
  explicit Robot(std::uint64_t room_kept = 0, std::uint64_t accepted = 0)
      : counters(std::make_shared<security::MemoryCounterStore>(1, accepted)),
        room_counters(std::make_shared<security::MemoryCounterStore>(1, room_kept)) {
    link::LinkOptions o;
    o.address = 1;
    o.key = test_key(1);
    o.counters = counters;
    o.room_key = kRoomKey;
    o.room_counters = room_counters;
    o.wall_clock = [] { return kToday; };
    link = link::make_link(p, o);
    receiver = link->receiver();
  }
  link::Reception hear(const link::TransmitFrame& frame) {
    const auto got = test_support::hear_alone(*link, *receiver, frame.audio);
    EXPECT_EQ(got.size(), 1u);
    return got.empty() ? link::Reception{} : got.front();
  }
  std::shared_ptr<security::MemoryCounterStore> counters, room_counters;
  std::unique_ptr<link::Link> link;
  std::unique_ptr<link::FrameReceiver> receiver;
};

bool stopped(const link::Reception& r) {
  return r.event == link::ReceptionEvent::Command && r.command && std::holds_alternative<command::Stop>(*r.command);
}

link::TransmitFrame room_stop(std::uint64_t counter) { return sender(kRoomKey, counter)->plan(command::Stop{true})[0]; }

}  // namespace

TEST(StopAlways, ARoomStopFromAClockADayFastOrAPlantedCounterStopsButIsNotKept) {
  for (const std::uint64_t ahead : {counter_at(kToday + hours(24)), kPlanted}) {
    Robot robot;
    const auto r = robot.hear(room_stop(ahead));
    EXPECT_TRUE(stopped(r)) << r.detail;
    EXPECT_NE(r.detail.find("ahead of this robot's clock"), std::string::npos) << r.detail;
    EXPECT_EQ(robot.room_counters->last_accepted(), 0u) << "nothing kept: the window is as it was";
    const auto next = robot.hear(room_stop(kTodayCounter));
    EXPECT_TRUE(stopped(next)) << "the next true stop --all: " << next.detail;
    EXPECT_EQ(robot.room_counters->last_accepted(), kTodayCounter);
  }
}

TEST(StopAlways, ARobotThatKeptAPlantedRoomCounterBeforeTheBoundRecoversAtTheNextTrueStop) {
  Robot robot(kPlanted);  // what the attacker left on every robot that heard it
  const auto r = robot.hear(room_stop(kTodayCounter));
  EXPECT_TRUE(stopped(r)) << r.detail;
  EXPECT_NE(r.detail.find("re-anchored"), std::string::npos) << r.detail;
  EXPECT_EQ(robot.room_counters->last_accepted(), kTodayCounter) << "the planted counter is gone from its state";
  const auto again = robot.hear(room_stop(kTodayCounter));
  EXPECT_EQ(again.event, link::ReceptionEvent::Repeat) << "played again: " << again.detail;
}

TEST(StopAlways, ARoomStopFromAClockADaySlowStopsTheRobotAndSoDoesTheTrueOneAfter) {
  Robot robot;
  const auto slow = robot.hear(room_stop(counter_at(kToday - hours(24))));
  EXPECT_TRUE(stopped(slow)) << slow.detail;
  const auto next = robot.hear(room_stop(kTodayCounter));
  EXPECT_TRUE(stopped(next)) << next.detail;
}

TEST(StopAlways, AKeyedStopIsOneFrameWithItsWholeCounterAndARobotOutOfStepTakesIt) {
  const auto key = test_key(1);
  const auto driver = sender(key, kTodayCounter, 1);
  // Just paired, every answer lost: the sender's frames go with a synchronisation first.
  const auto drive = driver->plan(command::DriveForward{40});
  ASSERT_EQ(drive.size(), 2u);
  ASSERT_TRUE(drive[0].synchronisation);
  const auto stop = driver->plan(command::Stop{});
  ASSERT_EQ(stop.size(), 1u) << "no synchronisation to wait behind";
  EXPECT_FALSE(stop[0].synchronisation) << "it is the stop itself";
  EXPECT_TRUE(stop[0].authenticated);
  // The robot heard neither the synchronisation nor the drive (lost, or an old state).
  for (const std::uint64_t accepted : {std::uint64_t{0}, kTodayCounter - 100'000}) {
    Robot robot(0, accepted);
    const auto r = robot.hear(stop[0]);
    EXPECT_TRUE(stopped(r)) << r.detail;
    EXPECT_TRUE(r.authenticated);
    EXPECT_EQ(robot.counters->last_accepted(), *stop[0].counter) << "in step from here";
    // Its answer carries the stop's tag: the sender confirms it.
    std::vector<float> answer = robot.link->answer_audio(r);
    answer.resize(answer.size() + 4800, 0.0f);
    bool confirmed = false;
    for (const auto& a : driver->answer_listener()->feed(answer)) confirmed |= a.ack && driver->answers(a, stop[0]);
    EXPECT_TRUE(confirmed);
    // Played again: answered, not taken twice; the next command completes from it.
    EXPECT_EQ(robot.hear(stop[0]).event, link::ReceptionEvent::Repeat);
    driver->confirmed(stop[0]);
    const auto next = driver->plan(command::DriveForward{20});
    ASSERT_EQ(next.size(), 1u) << "in step: no synchronisation";
    EXPECT_EQ(robot.hear(next[0]).event, link::ReceptionEvent::Command);
  }
}

TEST(StopAlways, ACommandPastTheRobotsClockIsRefusedAndNotKeptButAStopStillStops) {
  const auto key = test_key(1);
  const auto fast = sender(key, counter_at(kToday + hours(24)), 1);
  Robot robot(0, kTodayCounter - 50);
  const auto drive_fast = fast->plan(command::DriveForward{40});
  ASSERT_EQ(drive_fast.size(), 2u);
  const auto sync = robot.hear(drive_fast[0]);
  EXPECT_EQ(sync.event, link::ReceptionEvent::Refused) << sync.detail;
  EXPECT_NE(sync.detail.find("ahead of this robot's clock"), std::string::npos) << sync.detail;
  const auto drive = robot.hear(drive_fast[1]);  // its low bits complete to the robot's own window: MAC fails
  EXPECT_EQ(drive.event, link::ReceptionEvent::Refused) << drive.detail;
  EXPECT_FALSE(drive.command);
  const auto stop = robot.hear(fast->plan(command::Stop{})[0]);
  EXPECT_TRUE(stopped(stop)) << stop.detail;
  EXPECT_TRUE(stop.acknowledged());
  EXPECT_EQ(robot.counters->last_accepted(), kTodayCounter - 50) << "nothing from the fast clock was kept";
  // The true sender, whose clock is right, drives and stops the robot as before.
  const auto right = sender(key, kTodayCounter, 1);
  for (const auto& f : right->plan(command::DriveForward{30})) EXPECT_TRUE(robot.hear(f).acknowledged());
  EXPECT_TRUE(stopped(robot.hear(right->plan(command::Stop{})[0])));
}
