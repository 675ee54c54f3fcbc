// The admission's rules (link/admission_rules.h), one test per row: each row's scenario
// brings a robot on the bench (support/admission_bench.h) to the row's kind and condition,
// and the frame it hears must come out as the row says — the event, the reason, the answer,
// the authentication, and whether its counter was kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "link/admission_rules.h"
#include "support/admission_bench.h"

using namespace dtmf;
using namespace admission_bench;
using link::admission::Condition;
using link::admission::Rule;
using link::reading::FrameKind;

namespace {

const command::Velocity kGo{0.5, 0.0, 1.0};  // a 1 s lease
constexpr double kPastHorizonMs = link::kRenewalHorizonMs + 500;
constexpr double kPastLeaseMs = 1500;
constexpr double kWithinLeaseMs = 500;

// What the row's frame did.
struct Trial {
  std::unique_ptr<Bench> bench;
  std::optional<link::Reception> got;
  bool counter_kept = false;  // the robot's last accepted counter, or the room's, moved
  bool echo_counted = false;

  void start(Keys keys, std::uint64_t last_accepted = 0, std::uint64_t room_last = 0) {
    bench = std::make_unique<Bench>(keys, last_accepted, room_last);
  }
  // The row's frame: heard, and what it changed noted.
  void judge(reliability::FrameBits bits, int chords, double start_ms, bool intact = true) {
    const std::uint64_t last = bench->counters->last_accepted();
    const std::uint64_t room_last = bench->room_counters->last_accepted();
    const std::size_t echoes = bench->robot.echoes_ignored();
    got = bench->hear(bits, chords, start_ms, intact);
    counter_kept = bench->counters->last_accepted() != last || bench->room_counters->last_accepted() != room_last;
    echo_counted = bench->robot.echoes_ignored() != echoes;
  }
};

// Robots that took the velocity kGo at 0 ms: plain (numbered 3), or sealed (counter 5).
void plain_velocity(Trial& t) {
  t.start(Keys::None);
  t.bench->hear(plain(kMe, 3, payload(kGo)), kPlainChords, 0);
}
void sealed_velocity(Trial& t) {
  t.start(Keys::Own, 4);
  t.bench->hear(sealed_command(*own_key(), 5, kGo), kSealedChords, 0);
}
const auto kStop = payload(command::Stop{});
const auto kEveryRobot = payload(command::Stop{true});

struct Scenario {
  FrameKind kind;
  Condition condition;
  void (*stage)(Trial&);
};

// clang-format off
const Scenario kScenarios[] = {
  {FrameKind::Broken, Condition::AddressedHere, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kMe, 1, kStop), kPlainChords, 0, false); }},
  {FrameKind::Broken, Condition::AddressedElsewhere, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kOther, 1, kStop), kPlainChords, 0, false); }},
  {FrameKind::Echo, Condition::Always, [](Trial& t) {  // the older of the last two frames taken, heard again
    t.start(Keys::None); t.bench->hear(plain(kMe, 1, kStop), kPlainChords, 0);
    t.bench->hear(plain(kMe, 2, kStop), kPlainChords, 300); t.judge(plain(kMe, 1, kStop), kPlainChords, 600); }},
  {FrameKind::Elsewhere, Condition::Always, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kOther, 1, kStop), kPlainChords, 0); }},
  {FrameKind::PlainCommand, Condition::KeyedRobot, [](Trial& t) {
    t.start(Keys::Own); t.judge(plain(kMe, 1, kStop), kPlainChords, 0); }},
  {FrameKind::PlainCommand, Condition::Undecodable, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kMe, 1, kUndecodable), kPlainChords, 0); }},
  {FrameKind::PlainCommand, Condition::Repeat, [](Trial& t) {
    t.start(Keys::None); t.bench->hear(plain(kMe, 1, kStop), kPlainChords, 0);
    t.judge(plain(kMe, 1, kStop), kPlainChords, 300); }},
  {FrameKind::PlainCommand, Condition::Fresh, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kMe, 1, kStop), kPlainChords, 0); }},
  {FrameKind::PlainRoomStop, Condition::RoomKeyHeld, [](Trial& t) {
    t.start(Keys::OwnAndRoom); t.judge(plain(kOther, 1, kEveryRobot), kPlainChords, 0); }},
  {FrameKind::PlainRoomStop, Condition::KeyedRobot, [](Trial& t) {
    t.start(Keys::Own); t.judge(plain(kOther, 1, kEveryRobot), kPlainChords, 0); }},
  {FrameKind::PlainRoomStop, Condition::Fresh, [](Trial& t) {
    t.start(Keys::None); t.judge(plain(kOther, 1, kEveryRobot), kPlainChords, 0); }},
  {FrameKind::PlainRenewal, Condition::KeyedRobot, [](Trial& t) {
    t.start(Keys::Own); t.judge(plain_renewal(1, kMe, 3), kPlainChords, 0); }},
  {FrameKind::PlainRenewal, Condition::NotRenewable, [](Trial& t) {
    t.start(Keys::None); t.judge(plain_renewal(1, kMe, 3), kPlainChords, 0); }},
  {FrameKind::PlainRenewal, Condition::PastHorizon, [](Trial& t) {
    plain_velocity(t); t.judge(plain_renewal(1, kMe, 3), kPlainChords, kPastHorizonMs); }},
  {FrameKind::PlainRenewal, Condition::LeaseEnded, [](Trial& t) {
    plain_velocity(t); t.judge(plain_renewal(1, kMe, 3), kPlainChords, kPastLeaseMs); }},
  {FrameKind::PlainRenewal, Condition::Repeat, [](Trial& t) {
    plain_velocity(t); t.bench->hear(plain_renewal(1, kMe, 3), kPlainChords, kWithinLeaseMs);
    t.judge(plain_renewal(1, kMe, 3), kPlainChords, 2 * kWithinLeaseMs); }},
  {FrameKind::PlainRenewal, Condition::Fresh, [](Trial& t) {
    plain_velocity(t); t.judge(plain_renewal(1, kMe, 3), kPlainChords, kWithinLeaseMs); }},
  {FrameKind::RoomStop, Condition::Stale, [](Trial& t) {
    t.start(Keys::OwnAndRoom, 0, 1000); t.judge(room_stop(10), kSealedChords, 0); }},
  {FrameKind::RoomStop, Condition::Repeat, [](Trial& t) {
    t.start(Keys::OwnAndRoom); t.bench->hear(room_stop(2000), kSealedChords, 0);
    t.judge(room_stop(2000), kSealedChords, 300); }},
  {FrameKind::RoomStop, Condition::Ahead, [](Trial& t) {
    t.start(Keys::OwnAndRoom); t.judge(room_stop(ahead_counter()), kSealedChords, 0); }},
  {FrameKind::RoomStop, Condition::Fresh, [](Trial& t) {
    t.start(Keys::OwnAndRoom); t.judge(room_stop(2000), kSealedChords, 0); }},
  {FrameKind::JointRenewal, Condition::NumberedAsRenewed, [](Trial& t) {
    sealed_velocity(t); t.judge(joint_renewal(5, 5), kSealedChords, kWithinLeaseMs); }},
  {FrameKind::JointRenewal, Condition::PastHorizon, [](Trial& t) {
    sealed_velocity(t); t.judge(joint_renewal(6, 5), kSealedChords, kPastHorizonMs); }},
  {FrameKind::JointRenewal, Condition::LeaseEnded, [](Trial& t) {
    sealed_velocity(t); t.judge(joint_renewal(6, 5), kSealedChords, kPastLeaseMs); }},
  {FrameKind::JointRenewal, Condition::Repeat, [](Trial& t) {
    sealed_velocity(t); t.bench->hear(joint_renewal(6, 5), kSealedChords, kWithinLeaseMs);
    t.judge(joint_renewal(6, 5), kSealedChords, 2 * kWithinLeaseMs); }},
  {FrameKind::JointRenewal, Condition::Fresh, [](Trial& t) {
    sealed_velocity(t); t.judge(joint_renewal(6, 5), kSealedChords, kWithinLeaseMs); }},
  {FrameKind::Synchronisation, Condition::Ahead, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync(*own_key(), ahead_counter()), kSealedChords, 0); }},
  {FrameKind::Synchronisation, Condition::Stale, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync(*own_key(), 50), kSealedChords, 0); }},
  {FrameKind::Synchronisation, Condition::Repeat, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync(*own_key(), 100), kSealedChords, 0); }},
  {FrameKind::Synchronisation, Condition::Fresh, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync(*own_key(), 200), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::AheadStop, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync_stop(*own_key(), ahead_counter()), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::Ahead, [](Trial& t) {  // a store that kept a counter ahead before the bound
    t.start(Keys::Own, ahead_counter()); t.judge(sealed_command(*own_key(), ahead_counter() + 1, kGo), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::Stale, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sync_stop(*own_key(), 50), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::Repeat, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sealed_command(*own_key(), 100, command::Stop{}), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::Undecodable, [](Trial& t) {
    t.start(Keys::Own, 100);
    t.judge(sealed(*own_key(), kMe, reliability::SealedForm::Command, 101, kUndecodable), kSealedChords, 0); }},
  {FrameKind::SealedCommand, Condition::Fresh, [](Trial& t) {
    t.start(Keys::Own, 100); t.judge(sealed_command(*own_key(), 101, command::Stop{}), kSealedChords, 0); }},
  {FrameKind::Unverified, Condition::NoKey, [](Trial& t) {
    t.start(Keys::None); t.judge(sealed_command(*own_key(), 1, command::Stop{}), kSealedChords, 0); }},
  {FrameKind::Unverified, Condition::MacFails, [](Trial& t) {
    t.start(Keys::Own); t.judge(sealed_command(*other_key(), 1, command::Stop{}), kSealedChords, 0); }},
};
// clang-format on

const Scenario* scenario_for(const Rule& rule) {
  const auto* found = std::find_if(std::begin(kScenarios), std::end(kScenarios), [&](const Scenario& s) {
    return s.kind == rule.kind && s.condition == rule.condition;
  });
  return found == std::end(kScenarios) ? nullptr : found;
}

std::string rule_name(const Rule& rule) {
  return std::string(link::reading::kind_name(rule.kind)) + "_" +
         std::string(link::admission::condition_name(rule.condition));
}

// The test's name: the row's kind and condition ("sealed_command_ahead_stop").
std::string RowName(const testing::TestParamInfo<Rule>& info) { return rule_name(info.param); }

class AdmissionRule : public testing::TestWithParam<Rule> {};

}  // namespace

TEST(AdmissionRules, EveryRowHasOneScenarioAndEveryScenarioARow) {
  EXPECT_EQ(std::size(kScenarios), link::admission::kAdmissionRules.size());
  for (const Scenario& s : kScenarios) {
    EXPECT_NE(&link::admission::admission_rule(s.kind, s.condition), &link::admission::kUnlisted)
        << link::reading::kind_name(s.kind) << " " << link::admission::condition_name(s.condition);
  }
}

TEST_P(AdmissionRule, TheFrameComesOutAsTheRowSays) {
  const Rule& rule = GetParam();
  const Scenario* scenario = scenario_for(rule);
  ASSERT_NE(scenario, nullptr) << "no scenario for " << rule_name(rule);
  Trial t;
  scenario->stage(t);
  if (rule.verdict == link::admission::Verdict::Unheard) {
    EXPECT_FALSE(t.got.has_value()) << t.got->detail;
    EXPECT_EQ(t.echo_counted, rule.kind == FrameKind::Echo);
    return;
  }
  ASSERT_TRUE(t.got.has_value());
  const link::Reception& r = *t.got;
  EXPECT_EQ(r.event, link::admission::event_of(rule.verdict)) << r.detail;
  EXPECT_EQ(r.refusal, rule.refusal) << r.detail;
  EXPECT_EQ(r.answered, rule.answered) << r.detail;
  EXPECT_EQ(r.authenticated, rule.authenticated) << r.detail;
  EXPECT_EQ(t.counter_kept, rule.keeps_counter) << r.detail;
  EXPECT_EQ(r.command.has_value(),
            rule.verdict == link::admission::Verdict::Execute || rule.verdict == link::admission::Verdict::Renew)
      << r.detail;
  EXPECT_FALSE(r.detail.empty() && r.intact) << "every verdict on an intact frame says why";
}

INSTANTIATE_TEST_SUITE_P(EveryRow, AdmissionRule, testing::ValuesIn(link::admission::kAdmissionRules), RowName);
