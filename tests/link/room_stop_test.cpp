// A stop for every robot (docs/protocol.md §10, "A stop for every robot"): one frame that
// every robot in the room executes, whatever its address, and none answers. With a room key
// it is taken only sealed under that key, and only once: a recording played again stops
// nobody twice; without one, plain, by robots that take plain frames. Robots 1-3 have their
// own keys and share the room key, as `scripts/quickstart --robots 3` sets them up.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "command/command.h"
#include "command/word_codec.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "security/counter_store.h"
#include "security/link_key.h"
#include "support/robot_ear.h"
#include "support/test_key.h"

using namespace dtmf;

namespace {

const LinkProfile& p = profile_by_name("fast");

using test_support::test_key;

const auto kRoomKey = test_key(0x77);

// The sender's room link: the room key, its counters from a clock's value.
std::unique_ptr<link::Link> room_sender(std::shared_ptr<const security::LinkKey> room_key, std::uint64_t counter) {
  link::LinkOptions o;
  o.key = std::move(room_key);
  o.counters = std::make_shared<security::MemoryCounterStore>(counter);
  return link::make_link(p, o);
}

std::unique_ptr<link::Link> robot(std::uint8_t address, std::shared_ptr<const security::LinkKey> own,
                                  std::shared_ptr<const security::LinkKey> room_key) {
  link::LinkOptions o;
  o.address = address;
  o.key = std::move(own);
  o.room_key = std::move(room_key);
  return link::make_link(p, o);
}

// A robot's receiver, fed a track of frames with silence between them.
struct Ear {
  explicit Ear(const link::Link& listener) : robot(listener), receiver(listener.receiver()) {}
  std::vector<link::Reception> hear(const std::vector<float>& audio) {
    return test_support::hear_alone(robot, *receiver, audio);
  }
  const link::Link& robot;
  std::unique_ptr<link::FrameReceiver> receiver;
};

bool stops_every_robot(const link::Reception& r) {
  return r.command && command::every_robot(*r.command) && r.event == link::ReceptionEvent::Command;
}

}  // namespace

TEST(RoomStop, EveryKeyedRobotExecutesTheRoomStopOnceAndNoneAnswers) {
  const auto sender = room_sender(kRoomKey, 5000);
  const auto frames = sender->plan(command::Stop{true});
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(p.timing.broadcast_copies));
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames[0].broadcast && frames[0].authenticated);
  EXPECT_NE(frames[0].counter, frames[1].counter) << "each copy its own counter";
  for (std::uint8_t address = 1; address <= 3; ++address) {
    const auto r = robot(address, test_key(address), kRoomKey);
    Ear ear(*r);
    const auto first = ear.hear(frames[0].audio);
    ASSERT_EQ(first.size(), 1u) << "robot " << int(address);
    EXPECT_TRUE(stops_every_robot(first[0])) << first[0].detail;
    EXPECT_TRUE(first[0].authenticated);
    EXPECT_FALSE(first[0].answered);
    EXPECT_TRUE(r->answer_audio(first[0]).empty()) << "an answer from every robot at once";
    // The same frame played again (a recording): taken already, not executed again, not answered.
    const auto replayed = ear.hear(frames[0].audio);
    ASSERT_EQ(replayed.size(), 1u);
    EXPECT_FALSE(replayed[0].command.has_value()) << replayed[0].detail;
    EXPECT_FALSE(replayed[0].answered);
    // The second copy is a stop of its own.
    const auto second = ear.hear(frames[1].audio);
    ASSERT_EQ(second.size(), 1u);
    EXPECT_TRUE(stops_every_robot(second[0])) << second[0].detail;
  }
}

TEST(RoomStop, TwoSendersWhoseClocksDifferBothStopTheRobot) {
  const auto ahead = room_sender(kRoomKey, 900'000);
  const auto behind = room_sender(kRoomKey, 900'000 - 20 * 60);  // a clock a minute behind
  const auto r = robot(2, test_key(2), kRoomKey);
  Ear ear(*r);
  const auto a = ear.hear(ahead->plan(command::Stop{true}).front().audio);
  const auto b = ear.hear(behind->plan(command::Stop{true}).front().audio);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_TRUE(stops_every_robot(a[0])) << a[0].detail;
  EXPECT_TRUE(stops_every_robot(b[0])) << b[0].detail;
  // A recording older than the room's window (an hour) stops nobody.
  const auto old = room_sender(kRoomKey, 900'000 - 20 * 3600 - 1);
  const auto stale = ear.hear(old->plan(command::Stop{true}).front().audio);
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0].event, link::ReceptionEvent::Refused) << stale[0].detail;
  EXPECT_FALSE(stale[0].answered);
}

TEST(RoomStop, OnlyTheRoomKeyMakesAStopForEveryRobot) {
  // Sealed under another key (robot 2's own), with every_robot set: robot 3 does not take it.
  link::LinkOptions o;
  o.address = 0;
  o.key = test_key(2);
  const auto wrong = link::make_link(p, o)->plan(command::Stop{true}).front();
  for (const std::uint8_t address : {0, 3}) {
    const auto r = robot(address, test_key(3), kRoomKey);
    Ear ear(*r);
    for (const auto& heard : ear.hear(wrong.audio)) {
      EXPECT_FALSE(heard.command.has_value()) << "robot " << int(address) << ": " << heard.detail;
      EXPECT_FALSE(heard.answered);
    }
  }
  // A keyed robot without the room key refuses the room's stop, and keeps quiet.
  const auto r = robot(0, test_key(4), nullptr);
  Ear ear(*r);
  const auto heard = ear.hear(room_sender(kRoomKey, 10)->plan(command::Stop{true}).front().audio);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].event, link::ReceptionEvent::Refused);
  EXPECT_FALSE(heard[0].answered);
}

TEST(RoomStop, UnkeyedItIsPlainAndTakenOnlyByRobotsThatTakePlainFrames) {
  const auto sender = room_sender(nullptr, 1);
  const auto frames = sender->plan(command::Stop{true});
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_FALSE(frames[0].authenticated);
  for (std::uint8_t address = 0; address <= 7; ++address) {
    const auto r = robot(address, nullptr, nullptr);
    Ear ear(*r);
    const auto heard = ear.hear(frames[0].audio);
    ASSERT_EQ(heard.size(), 1u) << "robot " << int(address);
    EXPECT_TRUE(stops_every_robot(heard[0])) << heard[0].detail;
    EXPECT_TRUE(r->answer_audio(heard[0]).empty());
  }
  // With a key of its own, or the room key, a robot takes no plain stop for every robot.
  for (const bool room : {false, true}) {
    const auto r = room ? robot(1, nullptr, kRoomKey) : robot(1, test_key(1), nullptr);
    Ear ear(*r);
    const auto heard = ear.hear(frames[0].audio);
    ASSERT_EQ(heard.size(), 1u);
    EXPECT_EQ(heard[0].event, link::ReceptionEvent::Refused) << heard[0].detail;
    EXPECT_FALSE(heard[0].answered);
  }
  EXPECT_THROW(link::make_link(profile_by_name("seed"), {})->plan(command::Stop{true}), command::ParameterError)
      << "the seed's frames name no robot";
}

TEST(RoomStop, RobotTwosFramesPlayedToRobotThreeMoveNothing) {
  link::LinkOptions o;
  o.address = 2;
  o.key = test_key(2);
  const auto sender = link::make_link(p, o);
  const auto drive = sender->plan(command::DriveForward{60});
  const auto r3 = robot(3, test_key(3), kRoomKey);
  Ear ear(*r3);
  for (const auto& f : drive) {
    for (const auto& heard : ear.hear(f.audio)) EXPECT_FALSE(heard.command.has_value()) << heard.detail;
  }
  // Nor robot 3 left at robot 2's address by mistake: the MAC is robot 2's key's.
  const auto misplaced = robot(2, test_key(3), kRoomKey);
  Ear ear2(*misplaced);
  for (const auto& f : drive) {
    for (const auto& heard : ear2.hear(f.audio)) {
      EXPECT_FALSE(heard.command.has_value()) << heard.detail;
      EXPECT_FALSE(heard.answered);
    }
  }
}
