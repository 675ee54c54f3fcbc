// Several robots in one room: an answer speaks only for the robot that gave it. Two senders
// drive robots 1 and 2, and their frames' sequence numbers (unkeyed) or counters (keyed)
// collide; each robot's answer, heard by both senders' ears, confirms only its own robot's
// frame. A robot keeps quiet about a frame it cannot check (sealed under another key) and
// about a broken frame whose address reads as another robot's: its answer would sound over
// the right robot's.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "command/command.h"
#include "link/frame_admission.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/command_frame.h"
#include "security/link_key.h"
#include "support/test_key.h"

using namespace dtmf;

namespace {

const LinkProfile& p = profile_by_name("fast");

using test_support::test_key;

link::LinkOptions options(std::uint8_t address, std::shared_ptr<const security::LinkKey> k) {
  link::LinkOptions o;
  o.address = address;
  o.key = std::move(k);
  o.first_sequence = 5;  // every sender starts at the same number: they collide
  return o;
}

// What `sender`'s ear makes of `audio` (an answer, clean, after a little silence).
std::vector<link::Answer> heard_by(const link::Link& sender, const std::vector<float>& audio) {
  std::vector<float> track(static_cast<std::size_t>(p.samples_for_ms(200)), 0.0f);
  track.insert(track.begin() + static_cast<long>(p.samples_for_ms(50)), audio.begin(), audio.end());
  const auto ear = sender.answer_listener();
  std::vector<link::Answer> answers;
  const auto block = static_cast<std::size_t>(sender.answer_block_samples());
  for (std::size_t at = 0; at + block <= track.size(); at += block) {
    for (const link::Answer& a : ear->feed(std::span<const float>(track).subspan(at, block))) answers.push_back(a);
  }
  return answers;
}

// Whether anything `sender` hears in `audio` confirms (or, a NACK, ends) `frame`.
bool answers(const link::Link& sender, const std::vector<float>& audio, const link::TransmitFrame& frame) {
  bool any = false;
  for (const link::Answer& a : heard_by(sender, audio)) any = any || sender.answers(a, frame);
  return any;
}

struct TwoRobots {
  std::unique_ptr<link::Link> sender1, sender2, robot1, robot2;
  link::TransmitFrame frame1, frame2;
};

TwoRobots two_robots(std::shared_ptr<const security::LinkKey> key1, std::shared_ptr<const security::LinkKey> key2) {
  TwoRobots t;
  t.sender1 = link::make_link(p, options(1, key1));
  t.sender2 = link::make_link(p, options(2, key2));
  t.robot1 = link::make_link(p, options(1, key1));
  t.robot2 = link::make_link(p, options(2, key2));
  t.frame1 = t.sender1->plan(command::Stop{}).back();
  t.frame2 = t.sender2->plan(command::Stop{}).back();
  return t;
}

}  // namespace

TEST(FleetAnswers, UnkeyedAcksWithTheSameSequenceNumberConfirmOnlyTheirOwnRobotsFrame) {
  TwoRobots t = two_robots(nullptr, nullptr);
  ASSERT_EQ(t.frame1.sequence, t.frame2.sequence) << "the test needs colliding sequence numbers";
  const auto ack1 = t.robot1->answer_audio(link::intact_reception(t.frame1));
  const auto ack2 = t.robot2->answer_audio(link::intact_reception(t.frame2));
  // Each ear hears both ACKs, and reads the robot in each.
  const auto heard = heard_by(*t.sender1, ack2);
  ASSERT_FALSE(heard.empty()) << "robot 2's ACK was not heard at all";
  EXPECT_EQ(heard.front().address, 2);
  EXPECT_EQ(heard.front().sequence, t.frame2.sequence);
  EXPECT_TRUE(answers(*t.sender1, ack1, t.frame1));
  EXPECT_TRUE(answers(*t.sender2, ack2, t.frame2));
  EXPECT_FALSE(answers(*t.sender1, ack2, t.frame1)) << "robot 2's ACK confirmed robot 1's frame";
  EXPECT_FALSE(answers(*t.sender2, ack1, t.frame2)) << "robot 1's ACK confirmed robot 2's frame";
}

TEST(FleetAnswers, ANackEndsOnlyItsOwnRobotsFrame) {
  TwoRobots t = two_robots(nullptr, nullptr);
  link::Reception broken = link::intact_reception(t.frame2);
  broken.intact = false;
  const auto nack2 = t.robot2->answer_audio(broken);
  ASSERT_FALSE(nack2.empty());
  EXPECT_TRUE(answers(*t.sender2, nack2, t.frame2));
  EXPECT_FALSE(answers(*t.sender1, nack2, t.frame1)) << "robot 2's NACK ended robot 1's frame";
}

TEST(FleetAnswers, TaggedAcksWithTheSameCounterConfirmOnlyTheirOwnRobotsFrame) {
  // One key for the room (both robots hold it), then a key each.
  for (const bool room_key : {true, false}) {
    TwoRobots t = room_key ? two_robots(test_key(0x5a), test_key(0x5a)) : two_robots(test_key(0x5a), test_key(0x33));
    ASSERT_EQ(t.frame1.counter, t.frame2.counter) << "the test needs colliding counters";
    const auto ack1 = t.robot1->answer_audio(link::intact_reception(t.frame1));
    const auto ack2 = t.robot2->answer_audio(link::intact_reception(t.frame2));
    EXPECT_TRUE(answers(*t.sender1, ack1, t.frame1)) << (room_key ? "room key" : "own keys");
    EXPECT_TRUE(answers(*t.sender2, ack2, t.frame2)) << (room_key ? "room key" : "own keys");
    EXPECT_FALSE(answers(*t.sender1, ack2, t.frame1)) << (room_key ? "room key" : "own keys");
    EXPECT_FALSE(answers(*t.sender2, ack1, t.frame2)) << (room_key ? "room key" : "own keys");
  }
}

TEST(FleetAnswers, ARobotLeavesAFrameSealedUnderAnotherKeyUnansweredAndUnexecuted) {
  // Both robots left at the default address, each with its own key.
  const auto sender = link::make_link(p, options(0, test_key(0x5a)));
  const auto other_robot = link::make_link(p, options(0, test_key(0x33)));
  const auto own_robot = link::make_link(p, options(0, test_key(0x5a)));
  const link::TransmitFrame frame = sender->plan(command::Stop{}).back();
  std::vector<float> track(static_cast<std::size_t>(p.samples_for_ms(100)), 0.0f);
  track.insert(track.end(), frame.audio.begin(), frame.audio.end());
  track.resize(track.size() + static_cast<std::size_t>(p.samples_for_ms(600)), 0.0f);
  const auto hear = [&](const link::Link& robot) {
    std::vector<link::Reception> got;
    const auto receiver = robot.receiver();
    const auto block = static_cast<std::size_t>(robot.receiver_block_samples());
    for (std::size_t at = 0; at + block <= track.size(); at += block) {
      for (const auto& r : receiver->feed(std::span<const float>(track).subspan(at, block))) got.push_back(r);
    }
    return got;
  };
  const auto others = hear(*other_robot);
  ASSERT_EQ(others.size(), 1u);
  EXPECT_EQ(others[0].event, link::ReceptionEvent::Refused);
  EXPECT_FALSE(others[0].command.has_value());
  EXPECT_FALSE(others[0].answered);
  EXPECT_TRUE(other_robot->answer_audio(others[0]).empty()) << "a NACK over the right robot's ACK";
  const auto owns = hear(*own_robot);
  ASSERT_EQ(owns.size(), 1u);
  EXPECT_TRUE(owns[0].acknowledged());
  EXPECT_TRUE(owns[0].answered);
  EXPECT_TRUE(answers(*sender, own_robot->answer_audio(owns[0]), frame));
}

TEST(FleetAnswers, ABrokenFrameIsNackedOnlyByTheRobotItsAddressReadsAs) {
  const auto sender = link::make_link(p, options(2, nullptr));
  const link::TransmitFrame frame = sender->plan(command::Stop{}).back();
  link::HeardHopFrame broken;
  broken.chords = 2;
  broken.intact = false;
  broken.bits = frame.bits;  // as read: the address bits right, the check failed
  for (const std::uint8_t address : {1, 2}) {
    link::FrameAdmission admission(p, options(address, nullptr));
    const auto r = admission.admit(broken);
    ASSERT_TRUE(r.has_value()) << "a broken frame is logged by every robot that hears it";
    EXPECT_FALSE(r->intact);
    EXPECT_FALSE(r->command.has_value());
    EXPECT_EQ(r->answered, address == 2) << "robot " << int(address);
  }
}
