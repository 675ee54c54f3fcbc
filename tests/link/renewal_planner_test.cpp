// The joint renewal's planner (link/renewal_planner.h), on its own: robots given by address,
// key and record, no link and no store. The frames it makes must be the very bits the former
// path (FastLink::plan_renewal, before the planner) played for the same keys and counters:
// the expected values below were printed by that path at commit 6af64fb.
#include "link/renewal_planner.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "command/command.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/frame_bits.h"
#include "security/counter_store.h"
#include "support/test_key.h"

using namespace dtmf;

namespace {

const LinkProfile& p = profile_by_name("fast");

const auto kKey1 = test_support::test_key(1);
const auto kKey2 = test_support::test_key(2);
const auto kKey3 = test_support::test_key(3);

link::RenewalParty keyed(std::uint8_t address, const security::LinkKey& key, std::uint64_t velocity_counter,
                         std::uint64_t fresh_counter) {
  link::RenewalParty party;
  party.address = address;
  party.key = &key;
  party.record.velocity_counter = velocity_counter;
  party.fresh_counter = fresh_counter;
  return party;
}

link::RenewalParty plain(std::uint8_t address, std::uint8_t velocity_sequence, std::uint64_t next_number = 0) {
  link::RenewalParty party;
  party.address = address;
  party.record.velocity_sequence = velocity_sequence;
  party.record.next_renewal_number = next_number;
  return party;
}

reliability::FrameBits bits(const char* decimal) { return reliability::FrameBits::parse_decimal(decimal); }

}  // namespace

TEST(RenewalPlanner, OneKeyedRobotsFrameIsTheFormerPaths) {
  // Its store began at 1: a synchronisation (1), the velocity (2), then 3 for the renewal.
  const std::vector parties{keyed(1, *kKey1, 2, 3)};
  const link::RenewalPlan plan = link::plan_joint_renewal(p, parties);
  ASSERT_TRUE(plan.frame);
  EXPECT_EQ(plan.frame->bits, bits("260183378774243923985300"));
  EXPECT_EQ(plan.frame->counter, 3u);
  EXPECT_EQ(plan.counter, 3u);
  EXPECT_EQ(plan.renewed, (std::vector<std::size_t>{0}));
  EXPECT_EQ(plan.numbered, (std::vector<std::size_t>{0}));
  EXPECT_TRUE(plan.frame->renewal && plan.frame->authenticated);
  EXPECT_FALSE(plan.frame->sequence) << "no answer names it";
  EXPECT_EQ(plan.frame->tone_ms, 153.75);
  EXPECT_EQ(plan.frame->next_frame_after_ms, 153.75) << "no answer to wait for";
}

TEST(RenewalPlanner, ThreeKeyedRobotsShareTheGreatestFreshCounter) {
  // Robot 2's store began at 40: its velocity was 41 and its fresh counter 42.
  const std::vector parties{keyed(1, *kKey1, 2, 3), keyed(2, *kKey2, 41, 42), keyed(3, *kKey3, 2, 3)};
  const link::RenewalPlan plan = link::plan_joint_renewal(p, parties);
  ASSERT_TRUE(plan.frame);
  EXPECT_EQ(plan.frame->bits, bits("301581375164064993782427"));
  EXPECT_EQ(plan.counter, 42u);
  EXPECT_EQ(plan.renewed, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(plan.frame->address, 1) << "named after its first slot";
}

TEST(RenewalPlanner, PlainFramesAreTheFormerPaths) {
  const std::vector one{plain(1, 0)};
  const link::RenewalPlan first = link::plan_joint_renewal(p, one);
  ASSERT_TRUE(first.frame);
  EXPECT_EQ(first.frame->bits, bits("7851335525361"));
  EXPECT_EQ(first.next_renewal_number, 1u);
  EXPECT_FALSE(first.frame->authenticated);
  EXPECT_FALSE(first.frame->sequence) << "no answer names it";
  EXPECT_EQ(first.frame->bit_count, 50);
  EXPECT_EQ(link::plan_joint_renewal(p, std::vector{plain(1, 0, 1)}).frame->bits, bits("16647428515378"))
      << "the next number";
  const std::vector three{plain(1, 0), plain(2, 0), plain(3, 0)};
  const link::RenewalPlan all = link::plan_joint_renewal(p, three);
  ASSERT_TRUE(all.frame);
  EXPECT_EQ(all.frame->bits, bits("7851471801673"));
  EXPECT_EQ(all.renewed, (std::vector<std::size_t>{0, 1, 2}));
}

TEST(RenewalPlanner, ThroughTheLinksTheFrameAndTheCountersAreTheFormerPaths) {
  link::LinkOptions o;
  o.address = 1;
  o.key = kKey1;
  const auto store = std::make_shared<security::MemoryCounterStore>(1);
  o.counters = store;
  const auto sender = link::make_link(p, o);
  for (const auto& f : sender->plan(command::Velocity{0.5, 0.0, 2.0})) sender->confirmed(f);
  const std::vector<link::Link*> links{sender.get()};
  const auto first = sender->plan_renewal(links);
  const auto second = sender->plan_renewal(links);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->frame.bits, bits("260183378774243923985300"));
  EXPECT_EQ(second->frame.bits, bits("230519847237540277912991"));
  EXPECT_EQ(second->frame.counter, 5u);
  EXPECT_EQ(store->next_counter(), 7u) << "each renewal used its counters as before";
}

TEST(RenewalPlanner, KeyedAndPlainRobotsAreRefusedTogetherWithAClearError) {
  const std::vector parties{keyed(1, *kKey1, 2, 3), plain(2, 0)};
  try {
    link::plan_joint_renewal(p, parties);
    FAIL() << "mixed robots planned";
  } catch (const link::MixedRenewal& e) {
    EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what();
  }
  // Through the links too: nothing is drawn from the keyed robot's store first.
  link::LinkOptions with_key;
  with_key.address = 1;
  with_key.key = kKey1;
  const auto store = std::make_shared<security::MemoryCounterStore>(10);
  with_key.counters = store;
  link::LinkOptions without;
  without.address = 2;
  const auto a = link::make_link(p, with_key);
  const auto b = link::make_link(p, without);
  a->plan(command::Velocity{0.5, 0.0, 2.0});
  b->plan(command::Velocity{0.5, 0.0, 2.0});
  const std::uint64_t next_before = store->next_counter();
  EXPECT_THROW(a->plan_renewal(std::vector<link::Link*>{a.get(), b.get()}), link::MixedRenewal);
  EXPECT_EQ(store->next_counter(), next_before + 1);
}

TEST(RenewalPlanner, ARobotWhoseLastVelocityIsUnknownIsLeftOutAndNotNumbered) {
  link::RenewalParty unknown = keyed(2, *kKey2, 0, 50);
  unknown.record.velocity_counter.reset();  // its last frame was no velocity, or none was sent
  const std::vector parties{unknown, keyed(3, *kKey3, 7, 8)};
  const link::RenewalPlan plan = link::plan_joint_renewal(p, parties);
  ASSERT_TRUE(plan.frame);
  EXPECT_EQ(plan.renewed, (std::vector<std::size_t>{1}));
  EXPECT_EQ(plan.numbered, (std::vector<std::size_t>{1}));
  EXPECT_EQ(plan.counter, 8u) << "its fresh counter is not the renewal's";
  EXPECT_EQ(plan.frame->address, 3);
  const link::RenewalPlan none = link::plan_joint_renewal(p, std::vector{unknown});
  EXPECT_FALSE(none.frame);
  EXPECT_TRUE(none.numbered.empty());
  EXPECT_FALSE(none.counter);
  link::RenewalParty plain_unknown = plain(1, 0);
  plain_unknown.record.velocity_sequence.reset();
  EXPECT_FALSE(link::plan_joint_renewal(p, std::vector{plain_unknown}).frame);
  EXPECT_FALSE(link::plan_joint_renewal(p, std::vector<link::RenewalParty>{}).frame) << "no robot: nothing";
}

TEST(RenewalPlanner, AtMostThreeRobotsInOrder) {
  const std::vector parties{plain(1, 3), plain(2, 4), plain(3, 5), plain(4, 6)};
  const link::RenewalPlan plan = link::plan_joint_renewal(p, parties);
  EXPECT_EQ(plan.renewed, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(plan.numbered, (std::vector<std::size_t>{0, 1, 2})) << "the fourth waits for the next renewal";
}

TEST(RenewalPlanner, ARobotThatCannotCompleteTheCounterIsNumberedButLeftOut) {
  // Robot 2's fresh counter, 5002, lies a window or more past robot 1's velocity (2).
  const std::vector parties{keyed(1, *kKey1, 2, 3), keyed(2, *kKey2, 5001, 5002)};
  const link::RenewalPlan plan = link::plan_joint_renewal(p, parties);
  ASSERT_TRUE(plan.frame);
  EXPECT_EQ(plan.frame->bits, bits("346357961266573422856956"));
  EXPECT_EQ(plan.renewed, (std::vector<std::size_t>{1}));
  EXPECT_EQ(plan.numbered, (std::vector<std::size_t>{0, 1})) << "robot 1's store must skip the counter too";
  EXPECT_EQ(plan.frame->address, 2);
  // Alone, it renews nothing, and its counter is still used.
  const link::RenewalPlan alone = link::plan_joint_renewal(p, std::vector{keyed(1, *kKey1, 2, 600)});
  EXPECT_FALSE(alone.frame);
  EXPECT_EQ(alone.counter, 600u);
  EXPECT_EQ(alone.numbered, (std::vector<std::size_t>{0}));
}

TEST(RenewalPlanner, AKeyedRobotWithoutAFreshCounterIsAnError) {
  link::RenewalParty party = keyed(1, *kKey1, 2, 3);
  party.fresh_counter.reset();
  EXPECT_THROW(link::plan_joint_renewal(p, std::vector{party}), std::invalid_argument);
}

TEST(RenewalPlanner, ThePlanDependsOnItsInputsAlone) {
  const std::vector parties{keyed(1, *kKey1, 2, 3), keyed(3, *kKey3, 2, 3)};
  const link::RenewalPlan a = link::plan_joint_renewal(p, parties);
  const link::RenewalPlan b = link::plan_joint_renewal(p, parties);
  ASSERT_TRUE(a.frame && b.frame);
  EXPECT_EQ(a.frame->bits, b.frame->bits);
  EXPECT_EQ(a.frame->audio, b.frame->audio);
}
