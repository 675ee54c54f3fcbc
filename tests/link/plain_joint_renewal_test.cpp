// A joint renewal without keys (reliability/plain_renewal.h; docs/protocol.md §10, "Renewing
// leases together"): one unanswered 50-bit frame that renews the velocities of up to three
// unkeyed robots, each bound to the sequence number of the velocity frame it took last. The
// robots' sequence numbers start alike (first_sequence 0), so only the addresses tell their
// slots apart.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "command/command.h"
#include "link/frame_admission.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "support/robot_ear.h"
#include "support/test_key.h"

using namespace dtmf;

namespace {

const LinkProfile& p = profile_by_name("fast");

struct Pair {
  std::unique_ptr<link::Link> sender;
  std::unique_ptr<link::Link> robot;
  std::unique_ptr<link::FrameReceiver> receiver;
};

Pair pair(std::uint8_t address, link::LinkOptions robot_options = {}) {
  link::LinkOptions o;
  o.address = address;
  o.first_sequence = 0;
  auto sender = link::make_link(p, o);
  robot_options.address = address;
  auto robot = link::make_link(p, robot_options);
  auto receiver = robot->receiver();
  return {std::move(sender), std::move(robot), std::move(receiver)};
}

// What the robot made of `audio`, played after silence and followed by its answer's time.
std::vector<link::Reception> hear(Pair& r, const std::vector<float>& audio) {
  return test_support::hear_alone(*r.robot, *r.receiver, audio);
}

void drive(Pair& r, const command::Command& command) {
  for (const auto& f : r.sender->plan(command)) {
    const auto got = hear(r, f.audio);
    ASSERT_EQ(got.size(), 1u);
    ASSERT_TRUE(got[0].acknowledged()) << got[0].detail;
  }
}

command::Velocity as_taken(const Pair& r, const command::Velocity& v) {
  return std::get<command::Velocity>(r.robot->as_received(v));
}

bool renewed(const std::vector<link::Reception>& got, const command::Velocity& velocity) {
  return got.size() == 1 && got[0].event == link::ReceptionEvent::Renewed && got[0].command &&
         std::get<command::Velocity>(*got[0].command) == velocity && !got[0].answered && !got[0].authenticated;
}

bool nothing_executed(const std::vector<link::Reception>& got) {
  for (const auto& r : got) {
    if (r.command || r.answered) return false;
  }
  return true;
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

TEST(PlainJointRenewal, OneFrameRenewsThreeRobotsEachItsOwnVelocityAndNoneAnswers) {
  std::vector<Pair> robots;
  for (std::uint8_t a = 1; a <= 3; ++a) robots.push_back(pair(a));
  const std::array velocities{kAhead, kLeft, kBack};
  for (std::size_t i = 0; i < 3; ++i) drive(robots[i], velocities[i]);
  const auto planned = robots[0].sender->plan_renewal(senders(robots));
  ASSERT_TRUE(planned);
  EXPECT_EQ(planned->renewed, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(planned->frame.renewal);
  EXPECT_FALSE(planned->frame.authenticated);
  EXPECT_EQ(planned->frame.bit_count, 50);
  EXPECT_FALSE(planned->frame.sequence) << "no answer names it";
  for (std::size_t i = 0; i < 3; ++i) {
    const auto got = hear(robots[i], planned->frame.audio);
    EXPECT_TRUE(renewed(got, as_taken(robots[i], velocities[i])))
        << "robot " << i + 1 << ": " << (got.empty() ? "nothing" : got[0].detail);
    ASSERT_FALSE(got.empty());
    EXPECT_TRUE(robots[i].robot->answer_audio(got[0]).empty()) << "three robots would answer at once";
  }
}

TEST(PlainJointRenewal, EachRenewalIsTakenOnceAndItsEchoNever) {
  std::vector<Pair> robots;
  robots.push_back(pair(2));
  drive(robots[0], kAhead);
  const auto links = senders(robots);
  const auto first = robots[0].sender->plan_renewal(links);
  const auto second = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(first && second);
  EXPECT_NE(first->frame.bits, second->frame.bits) << "the next renewal would pass for the last one's echo";
  ASSERT_TRUE(renewed(hear(robots[0], first->frame.audio), as_taken(robots[0], kAhead)));
  const auto again = hear(robots[0], first->frame.audio);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].event, link::ReceptionEvent::Repeat) << again[0].detail;
  EXPECT_TRUE(nothing_executed(again)) << "a renewal's echo would stretch the lease past the sender's last word";
  EXPECT_TRUE(renewed(hear(robots[0], second->frame.audio), as_taken(robots[0], kAhead)));
  EXPECT_TRUE(nothing_executed(hear(robots[0], first->frame.audio))) << "the first, played after the second";
}

TEST(PlainJointRenewal, AVelocityIsRenewedForSixSecondsAfterItsFrameAtMost) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  drive(robots[0], kAhead);
  const auto links = senders(robots);
  const auto early = robots[0].sender->plan_renewal(links);
  const auto late = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(early && late);
  EXPECT_EQ(hear(robots[0], early->frame.audio)[0].event, link::ReceptionEvent::Renewed);
  hear(robots[0], std::vector<float>(static_cast<std::size_t>(p.samples_for_ms(link::kRenewalHorizonMs)), 0.0f));
  const auto played = hear(robots[0], late->frame.audio);
  ASSERT_EQ(played.size(), 1u);
  EXPECT_EQ(played[0].event, link::ReceptionEvent::Refused) << played[0].detail;
  EXPECT_TRUE(nothing_executed(played));
  drive(robots[0], kAhead);  // the velocity sent again renews anew
  const auto again = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(again);
  EXPECT_TRUE(renewed(hear(robots[0], again->frame.audio), as_taken(robots[0], kAhead)));
}

TEST(PlainJointRenewal, RenewsOnlyTheVelocityTheRobotTookLastAndNothingAfterAStop) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  robots.push_back(pair(2));
  drive(robots[0], kAhead);
  drive(robots[1], kAhead);
  // Robot 2 misses its next velocity: the renewal names that frame's number, not the one
  // robot 2 holds, and renews nothing there.
  robots[1].sender->plan(kBack);
  const auto links = senders(robots);
  const auto planned = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(planned);
  EXPECT_TRUE(renewed(hear(robots[0], planned->frame.audio), as_taken(robots[0], kAhead)));
  const auto missed = hear(robots[1], planned->frame.audio);
  ASSERT_EQ(missed.size(), 1u);
  EXPECT_EQ(missed[0].event, link::ReceptionEvent::Ignored) << missed[0].detail;
  EXPECT_TRUE(nothing_executed(missed));
  // Robot 1 takes a stop: a renewal of the velocity before it, made before the stop and
  // played after it, renews nothing; and its sender plans no renewal of robot 1 any more.
  const auto before_stop = robots[0].sender->plan_renewal(links);
  drive(robots[0], command::Stop{});
  EXPECT_TRUE(nothing_executed(hear(robots[0], before_stop->frame.audio)));
  const auto after = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->renewed, (std::vector<std::size_t>{1})) << "robot 1 stopped: not renewed";
}

TEST(PlainJointRenewal, RobotsWhoseSequenceNumbersCollideTakeOnlyTheirOwnSlot) {
  // Robots 1, 2 and 3 took velocities numbered alike (every sender started at 0). A renewal
  // of robots 1 and 2 moves neither of them with the other's velocity, and robot 3, named in
  // no slot, takes nothing.
  std::vector<Pair> robots;
  for (std::uint8_t a = 1; a <= 3; ++a) robots.push_back(pair(a));
  drive(robots[0], kAhead);
  drive(robots[1], kLeft);
  drive(robots[2], kBack);
  auto links = senders(robots);
  links.pop_back();
  const auto planned = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(planned);
  EXPECT_TRUE(renewed(hear(robots[0], planned->frame.audio), as_taken(robots[0], kAhead)));
  EXPECT_TRUE(renewed(hear(robots[1], planned->frame.audio), as_taken(robots[1], kLeft)));
  EXPECT_TRUE(hear(robots[2], planned->frame.audio).empty()) << "another robot's renewal is not robot 3's business";
}

TEST(PlainJointRenewal, ARobotWithAKeyTakesNoPlainRenewal) {
  // A keyed robot that lets plain frames in (--accept-unauthenticated) took a sealed velocity.
  // A plain renewal, which anyone can play, must not keep it moving, even one whose slot names
  // a number equal to that velocity's counter.
  link::LinkOptions keyed;
  keyed.key = test_support::test_key(1);
  keyed.accept_unauthenticated = true;
  std::vector<Pair> robots;
  robots.push_back(pair(1, keyed));
  link::LinkOptions sealing = keyed;
  sealing.address = 1;
  const auto sealed_sender = link::make_link(p, sealing);
  std::uint64_t counter = 0;
  for (const auto& f : sealed_sender->plan(kAhead)) {
    ASSERT_TRUE(hear(robots[0], f.audio)[0].acknowledged());
    counter = *f.counter;
  }
  ASSERT_LT(counter, 16u);
  link::LinkOptions plain;
  plain.address = 1;
  plain.first_sequence = static_cast<std::uint8_t>(counter);
  const auto plain_sender = link::make_link(p, plain);
  plain_sender->plan(kAhead);  // not heard: the renewal names its number, the sealed velocity's counter
  const auto planned = plain_sender->plan_renewal(std::vector<link::Link*>{plain_sender.get()});
  ASSERT_TRUE(planned);
  EXPECT_TRUE(nothing_executed(hear(robots[0], planned->frame.audio)));
  // A robot with a key that takes only sealed frames refuses it, unanswered, whatever it holds.
  link::LinkOptions sealed_only;
  sealed_only.key = test_support::test_key(1);
  robots.push_back(pair(1, sealed_only));
  const auto got = hear(robots[1], planned->frame.audio);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].event, link::ReceptionEvent::Refused) << got[0].detail;
  EXPECT_TRUE(nothing_executed(got));
}

// A renewal that begins after the velocity's lease ran out renews nothing: the robot stopped,
// and a renewal the air delayed (or a recording of one) must not set it moving again
// (TeleopE2E saw one heard 200 ms after the lease ended, once the server had been killed).
TEST(PlainJointRenewal, ARenewalAfterTheLeaseRanOutSetsNoStoppedRobotMoving) {
  std::vector<Pair> robots;
  robots.push_back(pair(1));
  drive(robots[0], kLeft);  // a 1 s lease
  const auto links = senders(robots);
  const auto in_time = robots[0].sender->plan_renewal(links);
  const auto too_late = robots[0].sender->plan_renewal(links);
  ASSERT_TRUE(in_time && too_late);
  ASSERT_TRUE(renewed(hear(robots[0], in_time->frame.audio), as_taken(robots[0], kLeft)));
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
  EXPECT_TRUE(renewed(hear(robots[0], again->frame.audio), as_taken(robots[0], kLeft)));
}
