// The sender's core in simulated time (server/core/sender_core.h): no thread, no sleep, no
// clock. Each test drives next() at the times the core names and gives it answers as its
// ears would, then reads the events it made: what went on the air, when, and why.
#include "sender_core.h"

#include <gtest/gtest.h>

#include "profile/link_profile.h"

using namespace dtmf;
using namespace dtmf::server;
using Kind = ProgressEvent::Kind;

namespace {

std::vector<RobotLinks> one_fast_robot() {
  std::vector<RobotLinks> robots(1);
  robots.front().links = link::make_links({});
  return robots;
}

TransmitterOptions quiet_room() {
  TransmitterOptions o;
  o.listen_before_talk = false;  // alone in the room: no other sender to defer to
  return o;
}

class Sim {
 public:
  explicit Sim(TransmitterOptions options = quiet_room())
      : core(one_fast_robot(), fast_profile(), options, {}), link(core.link_of(fast_profile())) {}

  // Submits `command` for the robot now, as a caller that gives up unconfirmed (or asks, with
  // `decision`); a Stop goes to the front, as callers send it.
  std::shared_ptr<Job> submit(const command::Command& command, Policy policy = Policy::Fail,
                              std::chrono::milliseconds decision = std::chrono::seconds(1)) {
    return taken(offer(command, policy, decision));
  }
  // The same, refused or not.
  Submitted offer(const command::Command& command, Policy policy = Policy::Fail,
                  std::chrono::milliseconds decision = std::chrono::seconds(1)) {
    const bool front = std::holds_alternative<command::Stop>(command);
    return core.submit(command, policy, decision, front, nullptr, 0, now);
  }
  // Runs the core until it plays a frame, at the times it names, up to `limit_ms`.
  std::optional<SenderCore::Play> until_play(double limit_ms) {
    while (true) {
      const SenderCore::Step step = core.next(now);
      take();
      if (const auto* p = std::get_if<SenderCore::Play>(&step)) return *p;
      const auto* w = std::get_if<SenderCore::WaitUntil>(&step);
      if (!w || w->at_ms > limit_ms) {
        now = limit_ms;
        return std::nullopt;
      }
      now = std::max(now, w->at_ms);
    }
  }
  // Runs the core to `until_ms`, at the times it names; what it plays meanwhile is counted.
  int run_until(double until_ms) {
    int played = 0;
    while (until_play(until_ms)) ++played;
    core.next(now);
    take();
    return played;
  }
  // The ACK its robot sends for `frame`, as the ears read it.
  void ack(const link::TransmitFrame& frame, double at_ms) {
    link::Answer answer;
    answer.ack = true;
    answer.sequence = frame.sequence;
    answer.lane = frame.answer_lane;
    answer.address = frame.address;
    answer.heard_ms = at_ms;
    core.hear_answer(HeardAnswer{&link, answer}, at_ms);
  }
  std::vector<Kind> kinds(const Job& job) const {
    std::vector<Kind> all;
    for (const auto& e : events)
      if (e.job.get() == &job) all.push_back(e.event.kind);
    return all;
  }
  const ProgressEvent& last(const Job& job) const {
    for (auto e = events.rbegin(); e != events.rend(); ++e)
      if (e->job.get() == &job) return e->event;
    throw std::logic_error("no event");
  }

  SenderCore core;
  const link::Link& link;
  double now = 0;
  std::vector<SenderCore::Emitted> events;

 private:
  void take() {
    for (auto& e : core.take_events()) events.push_back(std::move(e));
  }
};

}  // namespace

TEST(SenderCore, ACommandPlaysAndItsAckConfirmsItAllOnTheCoresClock) {
  Sim sim;
  const auto job = sim.submit(command::DriveForward{40});
  const auto play = sim.until_play(10);
  ASSERT_TRUE(play);
  EXPECT_EQ(play->job, job);
  EXPECT_EQ(play->start_ms, 0);
  const double tone_ms = play->frame->tone_ms;
  // Until the chord has sounded, then until its answer's deadline, nothing else happens.
  const auto during = sim.core.next(tone_ms / 2);
  ASSERT_TRUE(std::holds_alternative<SenderCore::WaitUntil>(during));
  EXPECT_EQ(std::get<SenderCore::WaitUntil>(during).at_ms, tone_ms);
  const auto waiting = sim.core.next(tone_ms);
  ASSERT_TRUE(std::holds_alternative<SenderCore::WaitUntil>(waiting));
  EXPECT_EQ(std::get<SenderCore::WaitUntil>(waiting).at_ms, fast_profile().timing.ack_timeout_ms);
  sim.ack(*play->frame, tone_ms + 40);
  sim.now = tone_ms + 41;
  sim.run_until(tone_ms + 41);
  EXPECT_EQ(sim.kinds(*job), (std::vector<Kind>{Kind::Queued, Kind::Transmitting, Kind::Ack, Kind::Confirmed}));
  EXPECT_EQ(sim.last(*job).outcome, Outcome::Confirmed);
  EXPECT_EQ(sim.last(*job).at_ms, tone_ms + 41);
  const auto& ack = sim.events[2].event;
  EXPECT_EQ(ack.response_time_ms, tone_ms + 40) << "from the chord's start to the ACK, in the core's time";
  EXPECT_EQ(ack.chord_ended_ms, tone_ms);
  EXPECT_EQ(sim.core.last_answered_ms(0), tone_ms + 40);
}

TEST(SenderCore, AnAckNamingAnotherFrameIsNoAnswerAndTheFrameGoesAgainAtItsDeadline) {
  Sim sim;
  const auto job = sim.submit(command::DriveForward{40});
  const auto first = sim.until_play(10);
  ASSERT_TRUE(first);
  link::TransmitFrame other = *first->frame;
  other.sequence = static_cast<std::uint8_t>(*other.sequence + 1);
  sim.ack(other, first->frame->tone_ms + 30);
  const auto again = sim.until_play(5000);
  ASSERT_TRUE(again) << "retransmitted";
  EXPECT_EQ(again->start_ms, fast_profile().timing.ack_timeout_ms) << "at the deadline, not at the stranger's ACK";
  EXPECT_EQ(sim.kinds(*job),
            (std::vector<Kind>{Kind::Queued, Kind::Transmitting, Kind::NoAnswer, Kind::Retransmitting}));
}

TEST(SenderCore, RetransmissionsUsedUpItAsksTheCallerAndTakesTheAnswerItGives) {
  Sim sim;
  const auto job = sim.submit(command::DriveForward{40}, Policy::Ask, std::chrono::seconds(5));
  const int played = sim.run_until(3000);
  EXPECT_EQ(played, 1 + fast_profile().timing.auto_retransmissions);
  ASSERT_EQ(sim.kinds(*job).back(), Kind::AwaitingDecision);
  const double asked_ms = sim.events.back().event.at_ms;
  // It waits for the caller until the decision timeout, and for nothing else.
  const auto waiting = sim.core.next(sim.now);
  ASSERT_TRUE(std::holds_alternative<SenderCore::WaitUntil>(waiting));
  EXPECT_EQ(std::get<SenderCore::WaitUntil>(waiting).at_ms, asked_ms + 5000);
  EXPECT_TRUE(job->decide(reliability::Decision::Continue));
  sim.run_until(sim.now + 1);
  EXPECT_EQ(sim.last(*job).outcome, Outcome::Continued);
}

TEST(SenderCore, AQuestionNobodyAnswersFailsTheCommandAtItsTimeout) {
  Sim sim;
  const auto job = sim.submit(command::DriveForward{40}, Policy::Ask, std::chrono::milliseconds(700));
  sim.run_until(3000);
  ASSERT_EQ(sim.last(*job).kind, Kind::Failed);
  EXPECT_EQ(sim.last(*job).detail, "no decision within the decision timeout");
  const double asked_ms = [&] {
    for (const auto& e : sim.events)
      if (e.event.kind == Kind::AwaitingDecision) return e.event.at_ms;
    return -1.0;
  }();
  EXPECT_EQ(sim.last(*job).at_ms, asked_ms + 700);
}

TEST(SenderCore, AStopOvertakesTheCommandWaitingForItsAnswerAndPlaysAtOnce) {
  Sim sim;
  const auto drive = sim.submit(command::DriveForward{40});
  const auto first = sim.until_play(10);
  ASSERT_TRUE(first);
  sim.now = first->frame->tone_ms + 5;  // the drive waits for its answer
  const double asked_ms = sim.now;
  const auto stop = sim.submit(command::Stop{});
  EXPECT_TRUE(drive->overtaken());
  const auto played = sim.until_play(sim.now + 1000);
  ASSERT_TRUE(played);
  EXPECT_EQ(played->job, stop);
  EXPECT_EQ(played->start_ms, std::max(asked_ms, first->start_ms + first->frame->next_frame_after_ms))
      << "as soon as the channel is free: the drive's answer is not awaited";
  EXPECT_EQ(sim.last(*drive).outcome, Outcome::Cancelled);
}

TEST(SenderCore, RenewalsThatFallDueGoBetweenACommandsRetransmissions) {
  Sim sim;
  // Due 300 ms after each frame for the robot: before the drive's retransmission.
  ASSERT_TRUE(sim.core.keep_renewed(0, fast_profile(), 300, 1000, 0));
  const auto drive = sim.submit(command::Velocity{0.1, 0, 1.0});
  std::vector<std::shared_ptr<Job>> played;
  while (const auto p = sim.until_play(2500)) played.push_back(p->job);
  ASSERT_GE(played.size(), 3u);
  EXPECT_EQ(played.front(), drive);
  const auto renewal = std::find_if(played.begin(), played.end(), [](const auto& j) { return j->renewal(); });
  ASSERT_NE(renewal, played.end()) << "a renewal went out while the drive was unanswered";
  EXPECT_NE(std::find(renewal, played.end(), drive), played.end()) << "and the drive went on after it";
  EXPECT_EQ(sim.last(**renewal).outcome, Outcome::Sent);
}

TEST(SenderCore, ACancelWhileTheAirIsBusyEndsTheCommandBeforeItPlays) {
  TransmitterOptions o;
  o.backoff_seed = 1;
  Sim sim(o);
  for (double t = 0; t < 2000; t += 4) sim.core.hear_level(-70, t);  // the room's floor
  sim.now = 2000;
  const auto job = sim.submit(command::DriveForward{40});
  sim.core.hear_level(-20, sim.now);  // another's chord, loud
  EXPECT_FALSE(sim.until_play(sim.now + 1)) << "it waits for the air";
  EXPECT_EQ(sim.kinds(*job).back(), Kind::WaitingForAir);
  job->cancel();
  EXPECT_FALSE(sim.until_play(sim.now + 1));
  EXPECT_EQ(sim.last(*job).outcome, Outcome::Cancelled);
  EXPECT_EQ(sim.kinds(*job), (std::vector<Kind>{Kind::Queued, Kind::WaitingForAir, Kind::Failed}));
}

TEST(SenderCore, AFullQueueRefusesCommandsButNeverAStop) {
  TransmitterOptions o = quiet_room();
  o.max_queue = 2;
  Sim sim(o);
  for (int i = 0; i < 2; ++i) sim.submit(command::Turn{10});
  const Submitted full = sim.offer(command::Turn{10});
  ASSERT_TRUE(std::holds_alternative<Refusal>(full));
  EXPECT_EQ(std::get<Refusal>(full).kind, Refusal::Kind::QueueFull);
  EXPECT_NE(std::get<Refusal>(full).why.find("send Stop"), std::string::npos) << std::get<Refusal>(full).why;
  EXPECT_TRUE(std::holds_alternative<std::shared_ptr<Job>>(sim.offer(command::Stop{})));
}

TEST(SenderCore, AtShutdownWhatWaitsEndsUnavailableAndNothingMorePlays) {
  Sim sim;
  const auto first = sim.submit(command::Turn{10});
  const auto second = sim.submit(command::Turn{20});
  ASSERT_TRUE(sim.until_play(10));
  sim.core.shutdown();
  EXPECT_EQ(sim.run_until(5000), 0);
  EXPECT_TRUE(sim.core.finished());
  EXPECT_EQ(sim.last(*first).outcome, Outcome::Unavailable);
  EXPECT_EQ(sim.last(*second).outcome, Outcome::Unavailable);
  const Submitted late = sim.offer(command::Turn{10});
  ASSERT_TRUE(std::holds_alternative<Refusal>(late));
  EXPECT_EQ(std::get<Refusal>(late).kind, Refusal::Kind::Unavailable);
}
