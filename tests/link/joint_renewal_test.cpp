// A joint renewal (docs/protocol.md §10, "Renewing leases together"): one unanswered frame
// that renews the velocities of up to three keyed robots, each slot under its robot's own key
// and bound to the velocity frame that robot took last. Robots 1-3 have their own keys and
// counters that start alike, so only the keys and the bound velocity tell their slots apart.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "command/command.h"
#include "command/command_payload.h"
#include "link/frame_admission.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/renewal_frame.h"
#include "reliability/sealed_frame.h"
#include "security/counter_store.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "support/robot_ear.h"
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
  return test_support::hear_alone(*r.robot, *r.receiver, audio);
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

const command::Velocity kAhead{0.5, 0.0, 2.0};  // the longest lease: these robots' clocks run on in silence
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
  // The first, captured and played after the second: taken already.
  const auto late = hear(robots[0], first->frame.audio);
  ASSERT_EQ(late.size(), 1u);
  EXPECT_FALSE(late[0].command);
  EXPECT_EQ(late[0].event, link::ReceptionEvent::Repeat);
  EXPECT_FALSE(late[0].answered);
}

TEST(JointRenewal, AVelocityIsRenewedForSixSecondsAfterItsFrameAtMost) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  drive(robots[0], kAhead);
  const auto links = senders(robots);
  const auto early = robots[0].sender->plan_renewal(links);
  const auto late = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(early && late);
  EXPECT_EQ(hear(robots[0], early->frame.audio)[0].event, link::ReceptionEvent::Renewed);
  // A renewal recorded (the robot did not hear it then) and played 6 s after the velocity's frame.
  hear(robots[0], std::vector<float>(static_cast<std::size_t>(p.samples_for_ms(link::kRenewalHorizonMs)), 0.0f));
  const auto played = hear(robots[0], late->frame.audio);
  ASSERT_EQ(played.size(), 1u);
  EXPECT_FALSE(played[0].command) << played[0].detail;
  EXPECT_EQ(played[0].event, link::ReceptionEvent::Refused);
  EXPECT_FALSE(played[0].answered);
  // The velocity sent again renews anew.
  drive(robots[0], kAhead);
  const auto again = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(again);
  EXPECT_EQ(hear(robots[0], again->frame.audio)[0].event, link::ReceptionEvent::Renewed);
}

TEST(JointRenewal, RenewalsLeaveTheCommandsCountersAlone) {
  // A renewal's counter is kept apart from the commands': a frame numbered before a renewal
  // but heard after it is still new to the robot, so a forged renewal that got through could
  // not make the sender's frames stale. (A second link on the same key and counter store
  // numbers that frame, as a second sender process on the same counter file would.)
  std::vector<Pair> robots;
  robots.push_back(pair(3));
  drive(robots[0], kAhead);
  const auto second = link::make_link(p, robots[0].sender->options());
  const auto earlier = second->plan(kBack);
  const auto renewal = robots[0].sender->plan_renewal(senders(robots));
  ASSERT_TRUE(renewal);
  ASSERT_EQ(earlier.size(), 1u);
  ASSERT_LT(earlier[0].counter, renewal->frame.counter);
  ASSERT_EQ(hear(robots[0], renewal->frame.audio)[0].event, link::ReceptionEvent::Renewed);
  const auto got = hear(robots[0], earlier[0].audio);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].event, link::ReceptionEvent::Command) << got[0].detail;
  EXPECT_FALSE(robots[0].sender->plan_renewal(std::vector<link::Link*>{})) << "no robot: nothing";
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
  // Robot 1's counter moved on with the renewal: its next frame carries all of it first, and
  // from then on it is in step with robot 2.
  const auto next = robots[0].sender->plan(kBack);
  ASSERT_EQ(next.size(), 2u);
  EXPECT_TRUE(next[0].synchronisation);
  for (const auto& f : next) {
    ASSERT_TRUE(hear(robots[0], f.audio)[0].acknowledged());
    robots[0].sender->confirmed(f);
  }
  const auto both = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(both);
  EXPECT_EQ(both->renewed, (std::vector<std::size_t>{0, 1}));
  EXPECT_TRUE(
      renewed(hear(robots[0], both->frame.audio), std::get<command::Velocity>(robots[0].robot->as_received(kBack))));
}

// A command whose bits also pass this robot's renewal slot by chance (one frame in about
// 2^18): found by search, it is still executed as the command (its 32-bit MAC holds), not
// taken for a renewal, which would leave it unexecuted and unanswered.
TEST(JointRenewal, ACommandThatAlsoReadsAsARenewalIsTheCommand) {
  const std::uint8_t address = 2;
  link::LinkOptions o;
  o.address = address;
  o.key = test_key(address);
  o.counters = std::make_shared<security::MemoryCounterStore>(1, 0);
  link::FrameAdmission robot(p, o);
  const auto seal = [&](std::uint64_t counter, const command::Command& c) {
    const std::uint32_t payload = command::encode_payload(c);
    reliability::SealedFrame f{address, reliability::SealedForm::Command, security::counter_low_bits(counter), payload,
                               security::frame_mac(*o.key, {address, 0, counter, payload})};
    return reliability::sealed_frame_pack(f);
  };
  const auto hear_bits = [&](reliability::FrameBits bits, double at_ms) {
    link::HeardHopFrame h;
    h.start_ms = at_ms;
    h.heard_ms = at_ms + 150;
    h.chords = 3;
    h.intact = true;
    h.bits = bits;
    return robot.admit(h);
  };
  const std::uint64_t velocity_counter = 1;
  ASSERT_EQ(hear_bits(seal(velocity_counter, kAhead), 0)->event, link::ReceptionEvent::Command);
  // Search the velocities the sender might send next (counter 2) for one whose bits pass a slot.
  std::optional<reliability::FrameBits> both;
  for (int linear = -2047; linear <= 2047 && !both; ++linear) {
    for (int angular = -127; angular <= 127 && !both; ++angular) {
      const command::Velocity v{linear / 2047.0, angular / 127.0, 1.0};
      const auto bits = seal(2, v);
      const auto renewal = reliability::renewal_frame_unpack(bits);
      const std::uint64_t counter = security::complete_counter(velocity_counter, renewal->counter_low);
      const std::uint32_t mac =
          security::frame_mac(*o.key, security::renewal_mac_input(address, counter, velocity_counter)) >>
          (32 - reliability::kRenewalMacBits);
      for (const auto& slot : renewal->slots) {
        if (counter != velocity_counter && slot.address == address && slot.mac == mac) both = bits;
      }
    }
  }
  ASSERT_TRUE(both) << "no velocity frame reads as a renewal too: search wider";
  const auto r = hear_bits(*both, 500);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->event, link::ReceptionEvent::Command) << r->detail;
  EXPECT_TRUE(r->answered);
  EXPECT_EQ(r->counter, 2u);
}

// A renewal that begins after the velocity's lease ran out renews nothing: the robot stopped,
// and a renewal the air delayed (or a recording of one) must not set it moving again
// (TeleopE2E saw one heard 200 ms after the lease ended, once the server had been killed).
TEST(JointRenewal, ARenewalAfterTheLeaseRanOutSetsNoStoppedRobotMoving) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  drive(robots[0], kLeft);  // a 1 s lease
  const auto links = senders(robots);
  const auto in_time = robots[0].sender->plan_renewal(links);
  const auto too_late = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(in_time && too_late);
  ASSERT_TRUE(
      renewed(hear(robots[0], in_time->frame.audio), std::get<command::Velocity>(robots[0].robot->as_received(kLeft))));
  hear(robots[0], std::vector<float>(static_cast<std::size_t>(p.samples_for_ms(1000 * kLeft.lease_s)), 0.0f));
  const auto played = hear(robots[0], too_late->frame.audio);
  ASSERT_EQ(played.size(), 1u);
  EXPECT_EQ(played[0].event, link::ReceptionEvent::Refused) << played[0].detail;
  EXPECT_NE(played[0].detail.find("lease ran out"), std::string::npos) << played[0].detail;
  EXPECT_FALSE(played[0].command);
  EXPECT_FALSE(played[0].answered);
  drive(robots[0], kLeft);  // a new velocity frame drives it again, and is renewed
  const auto again = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(again);
  EXPECT_TRUE(
      renewed(hear(robots[0], again->frame.audio), std::get<command::Velocity>(robots[0].robot->as_received(kLeft))));
}
