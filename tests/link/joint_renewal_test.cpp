// A joint renewal (docs/protocol.md §10, "Renewing leases together"): one unanswered frame
// that renews the velocities of up to three keyed robots, each slot under its robot's own key
// and bound to the velocity frame that robot took last. Robots 1-3 have their own keys and
// counters that start alike, so only the keys and the bound velocity tell their slots apart.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "command/command.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "security/counter_store.h"
#include "support/test_key.h"

using namespace dtmf;

namespace {

const LinkProfile& p = profile_by_name("fast");

using test_support::test_key;

struct Pair {
  std::unique_ptr<link::Link> sender;
  std::unique_ptr<link::Link> robot;
  std::unique_ptr<link::FrameReceiver> receiver;
};

Pair pair(std::uint8_t address, std::uint64_t first_counter = 1) {
  link::LinkOptions o;
  o.address = address;
  o.key = test_key(address);
  o.counters = std::make_shared<security::MemoryCounterStore>(first_counter);
  auto sender = link::make_link(p, o);
  o.counters = nullptr;  // the robot's own
  auto robot = link::make_link(p, o);
  auto receiver = robot->receiver();
  return {std::move(sender), std::move(robot), std::move(receiver)};
}

// What the robot made of `audio`, played after silence and followed by its answer's time.
std::vector<link::Reception> hear(Pair& r, const std::vector<float>& audio) {
  std::vector<float> track(static_cast<std::size_t>(p.samples_for_ms(100)), 0.0f);
  track.insert(track.end(), audio.begin(), audio.end());
  track.resize(track.size() + static_cast<std::size_t>(p.samples_for_ms(600)), 0.0f);
  std::vector<link::Reception> got;
  const auto block = static_cast<std::size_t>(r.robot->receiver_block_samples());
  for (std::size_t at = 0; at + block <= track.size(); at += block) {
    for (const auto& rec : r.receiver->feed(std::span<const float>(track).subspan(at, block))) got.push_back(rec);
  }
  return got;
}

// Sends `velocity` to the robot and has it take the frame (and the sender learn it did).
void drive(Pair& r, const command::Velocity& velocity) {
  const auto frames = r.sender->plan(velocity);
  for (const auto& f : frames) {
    const auto got = hear(r, f.audio);
    ASSERT_EQ(got.size(), 1u);
    ASSERT_TRUE(got[0].acknowledged()) << got[0].detail;
    r.sender->confirmed(f);
  }
}

bool renewed(const std::vector<link::Reception>& got, const command::Velocity& as_taken) {
  return got.size() == 1 && got[0].event == link::ReceptionEvent::Renewed && got[0].command &&
         std::get<command::Velocity>(*got[0].command) == as_taken && !got[0].answered && got[0].authenticated;
}

std::vector<link::Link*> senders(std::vector<Pair>& robots) {
  std::vector<link::Link*> out;
  for (auto& r : robots) out.push_back(r.sender.get());
  return out;
}

const command::Velocity kAhead{0.5, 0.0, 1.0};
const command::Velocity kLeft{0.25, 0.5, 1.0};
const command::Velocity kBack{-0.5, 0.0, 1.0};

}  // namespace

TEST(JointRenewal, OneFrameRenewsThreeRobotsEachItsOwnVelocityAndNoneAnswers) {
  std::vector<Pair> robots;
  for (std::uint8_t a = 1; a <= 3; ++a) robots.push_back(pair(a));
  const std::array velocities{kAhead, kLeft, kBack};
  for (std::size_t i = 0; i < 3; ++i) drive(robots[i], velocities[i]);
  const auto links = senders(robots);
  const auto planned = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(planned);
  EXPECT_EQ(planned->renewed, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(planned->frame.renewal && planned->frame.authenticated);
  EXPECT_EQ(planned->frame.bit_count, 80);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto got = hear(robots[i], planned->frame.audio);
    const auto as_taken = std::get<command::Velocity>(robots[i].robot->as_received(velocities[i]));
    EXPECT_TRUE(renewed(got, as_taken)) << "robot " << i + 1 << ": " << (got.empty() ? "nothing" : got[0].detail);
    ASSERT_FALSE(got.empty());
    EXPECT_TRUE(robots[i].robot->answer_audio(got[0]).empty()) << "three robots would answer at once";
    EXPECT_EQ(got[0].counter, planned->frame.counter);
  }
}

TEST(JointRenewal, PlayedAgainItRenewsNothing) {
  std::vector<Pair> robots;
  robots.push_back(pair(2));
  drive(robots[0], kAhead);
  const auto links = senders(robots);
  const auto first = robots[0].sender->plan_renewal(links);
  const auto second = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(first && second);
  ASSERT_TRUE(
      renewed(hear(robots[0], first->frame.audio), std::get<command::Velocity>(robots[0].robot->as_received(kAhead))));
  const auto again = hear(robots[0], first->frame.audio);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].event, link::ReceptionEvent::Repeat);
  EXPECT_FALSE(again[0].command) << "the same renewal executed twice";
  EXPECT_FALSE(again[0].answered);
  ASSERT_EQ(hear(robots[0], second->frame.audio)[0].event, link::ReceptionEvent::Renewed);
  // The first, captured and played after the second: its counter completes to a newer one, and
  // its MAC fails there. It is then read as a frame for robot 2 whose MAC fails: refused, unanswered.
  const auto late = hear(robots[0], first->frame.audio);
  ASSERT_EQ(late.size(), 1u);
  EXPECT_FALSE(late[0].command);
  EXPECT_EQ(late[0].event, link::ReceptionEvent::Refused);
  EXPECT_FALSE(late[0].answered);
}

TEST(JointRenewal, RenewsOnlyTheVelocityTheRobotTookLast) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  robots.push_back(pair(2));
  drive(robots[0], kAhead);
  drive(robots[1], kAhead);
  // Robot 2 misses its next velocity: the renewal, bound to the one it missed, renews nothing
  // there, so the robot's old velocity lapses with its lease.
  robots[1].sender->plan(kBack);
  const auto links = senders(robots);
  const auto planned = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(planned);
  EXPECT_TRUE(renewed(hear(robots[0], planned->frame.audio),
                      std::get<command::Velocity>(robots[0].robot->as_received(kAhead))));
  for (const auto& r : hear(robots[1], planned->frame.audio)) EXPECT_FALSE(r.command) << r.detail;
}

TEST(JointRenewal, NothingAfterAnotherCommandAndNoRobotRenewsAnothersSlot) {
  std::vector<Pair> robots;
  robots.push_back(pair(2));
  robots.push_back(pair(3));
  drive(robots[0], kAhead);
  drive(robots[1], kLeft);
  drive(robots[1], command::Velocity{0, 0, 1.0});
  const auto only_two = std::vector<link::Link*>{robots[0].sender.get()};
  const auto planned = robots[0].sender->plan_renewal(only_two);
  ASSERT_TRUE(planned);
  // Robot 3 hears robot 2's renewal: its address is in no slot, and robot 2's slot is under
  // robot 2's key, bound to robot 2's counter: not robot 3's business.
  for (const auto& r : hear(robots[1], planned->frame.audio)) EXPECT_FALSE(r.command) << r.detail;
  // A stop after the velocity: the sender renews nothing of robot 2's...
  robots[0].sender->plan(command::Stop{});
  EXPECT_FALSE(robots[0].sender->plan_renewal(only_two));
}

TEST(JointRenewal, ARobotThatCannotCompleteTheCounterIsLeftOutAndSynchronisesNext) {
  std::vector<Pair> robots;
  robots.push_back(pair(1, 1));
  robots.push_back(pair(2, 5000));  // 5000 counters ahead: robot 1 could not complete them
  drive(robots[0], kAhead);
  drive(robots[1], kLeft);
  const auto links = senders(robots);
  const auto planned = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(planned);
  EXPECT_EQ(planned->renewed, (std::vector<std::size_t>{1}));
  for (const auto& r : hear(robots[0], planned->frame.audio)) EXPECT_FALSE(r.command) << r.detail;
  // Robot 1's counter moved on with the renewal: its next frame carries all of it first.
  const auto next = robots[0].sender->plan(kBack);
  ASSERT_EQ(next.size(), 2u);
  EXPECT_TRUE(next[0].synchronisation);
}
