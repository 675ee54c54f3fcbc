// Reliability layer: the retry controller of the seed's Fig. 8, driven by events and times.
#include <gtest/gtest.h>

#include "reliability/retry_controller.h"

using namespace dtmf::reliability;

namespace {
constexpr RetryPolicy kSeedPolicy{1, 1500.0};
}

TEST(RetryController, AckOnTheFirstAttemptConfirmsWithItsResponseTime) {
  RetryController c(kSeedPolicy);
  EXPECT_EQ(c.start(), RetryState::TransmitPending);
  EXPECT_EQ(c.attempt(), 1);
  EXPECT_EQ(c.on_transmit_started(1000), RetryState::AwaitingAnswer);
  EXPECT_EQ(*c.deadline_ms(), 2500);
  EXPECT_EQ(c.on_tick(2000), RetryState::AwaitingAnswer);
  EXPECT_EQ(c.on_answer(Answer::Ack, 2350), RetryState::Confirmed);
  EXPECT_TRUE(c.finished());
  EXPECT_DOUBLE_EQ(*c.response_time_ms(), 1350);
}

TEST(RetryController, NackTriggersExactlyOneAutomaticRetransmission) {
  RetryController c(kSeedPolicy);
  c.start();
  c.on_transmit_started(0);
  EXPECT_EQ(c.on_answer(Answer::Nack, 400), RetryState::TransmitPending);
  EXPECT_EQ(c.attempt(), 2);
  EXPECT_EQ(c.last_miss(), Miss::Nack);
  c.on_transmit_started(1000);
  EXPECT_EQ(c.on_answer(Answer::Nack, 1400), RetryState::AwaitingDecision);
  EXPECT_EQ(c.attempt(), 2);
}

TEST(RetryController, TimeoutCountsLikeANack) {
  RetryController c(kSeedPolicy);
  c.start();
  c.on_transmit_started(0);
  EXPECT_EQ(c.on_tick(1499.9), RetryState::AwaitingAnswer);
  EXPECT_EQ(c.on_tick(1500), RetryState::TransmitPending);
  EXPECT_EQ(c.last_miss(), Miss::Timeout);
  EXPECT_FALSE(c.response_time_ms());
  c.on_transmit_started(2000);
  EXPECT_EQ(c.on_tick(3500), RetryState::AwaitingDecision);
}

TEST(RetryController, TheCallerMayRetransmitAsOftenAsItLikes) {
  RetryController c(kSeedPolicy);
  c.start();
  c.on_transmit_started(0);
  c.on_tick(1500);
  c.on_transmit_started(2000);
  c.on_tick(3500);
  for (int round = 0; round < 5; ++round) {
    ASSERT_EQ(c.state(), RetryState::AwaitingDecision);
    EXPECT_EQ(c.on_decision(Decision::Retransmit), RetryState::TransmitPending);
    EXPECT_EQ(c.attempt(), 3 + round);
    const double t = 4000.0 + 2000.0 * round;
    c.on_transmit_started(t);
    // Each further miss goes straight back to the caller: no more automatic retries.
    EXPECT_EQ(c.on_tick(t + 1500), RetryState::AwaitingDecision);
  }
  EXPECT_EQ(c.on_decision(Decision::Retransmit), RetryState::TransmitPending);
  c.on_transmit_started(20000);
  EXPECT_EQ(c.on_answer(Answer::Ack, 20500), RetryState::Confirmed);
  EXPECT_EQ(c.attempt(), 8);
}

TEST(RetryController, ContinueAndGiveUpEndTheFrame) {
  for (auto [decision, end] :
       {std::pair{Decision::Continue, RetryState::Continued}, std::pair{Decision::GiveUp, RetryState::Failed}}) {
    RetryController c(kSeedPolicy);
    c.start();
    c.on_transmit_started(0);
    c.on_answer(Answer::Nack, 100);
    c.on_transmit_started(1000);
    c.on_answer(Answer::Nack, 1100);
    EXPECT_EQ(c.on_decision(decision), end);
    EXPECT_TRUE(c.finished());
    // Nothing moves a finished frame.
    EXPECT_EQ(c.on_answer(Answer::Ack, 1200), end);
    EXPECT_EQ(c.on_tick(99999), end);
  }
}

TEST(RetryController, ALateAckStillConfirmsAndWithdrawsThePendingRetry) {
  RetryController c(kSeedPolicy);
  c.start();
  c.on_transmit_started(0);
  c.on_tick(1500);
  ASSERT_EQ(c.state(), RetryState::TransmitPending);
  EXPECT_EQ(c.on_answer(Answer::Ack, 1600), RetryState::Confirmed);
  EXPECT_DOUBLE_EQ(*c.response_time_ms(), 1600);
}

TEST(RetryController, DecisionsOutsideAwaitingDecisionAreIgnored) {
  RetryController c(kSeedPolicy);
  c.start();
  EXPECT_EQ(c.on_decision(Decision::GiveUp), RetryState::TransmitPending);
  EXPECT_EQ(c.on_answer(Answer::Nack, 5), RetryState::TransmitPending);  // nothing on air yet
}

TEST(RetryController, ZeroAutomaticRetriesAsksAtOnce) {
  RetryController c(RetryPolicy{0, 100});
  c.start();
  c.on_transmit_started(0);
  EXPECT_EQ(c.on_tick(100), RetryState::AwaitingDecision);
  EXPECT_EQ(c.attempt(), 1);
}
