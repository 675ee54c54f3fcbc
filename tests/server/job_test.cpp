// A job's decision handshake: the transmitter opens the question before it announces it, so
// a caller who answers the AWAITING_DECISION event at once is never told nothing waits.
#include "job.h"

#include <gtest/gtest.h>

#include "link/link.h"
#include "profile/link_profile.h"

using namespace dtmf;
using namespace dtmf::server;

namespace {

Job reset_job(std::chrono::milliseconds decision_timeout) {
  static const auto links = link::make_links({});
  return Job(*links.front(), command::Reset{}, Policy::Ask, decision_timeout, std::nullopt);
}

}  // namespace

TEST(Job, ADecisionBeforeTheQuestionIsOpenIsRefused) {
  auto job = reset_job(std::chrono::milliseconds(10));
  EXPECT_FALSE(job.decide(reliability::Decision::Continue));
  EXPECT_EQ(job.take_decision(), std::nullopt);  // and it was not kept for later
}

TEST(Job, ADecisionRightAfterTheQuestionOpensIsKeptUntilTheTransmitterWaits) {
  auto job = reset_job(std::chrono::seconds(60));
  job.open_decision();
  EXPECT_TRUE(job.decide(reliability::Decision::Retransmit));
  EXPECT_FALSE(job.decide(reliability::Decision::Continue));  // one answer per question
  EXPECT_EQ(job.take_decision(), reliability::Decision::Retransmit);
  EXPECT_EQ(job.take_decision(), std::nullopt);  // taken once
}

TEST(Job, ACancelOrADecisionWakesItsDriverAndAStopsOvertakingDoesNot) {
  auto job = reset_job(std::chrono::seconds(60));
  int woken = 0;
  job.on_change([&woken] { ++woken; });
  job.open_decision();
  EXPECT_TRUE(job.decide(reliability::Decision::Continue));
  EXPECT_EQ(woken, 1);
  job.overtake();  // the core overtakes it, and reads it itself
  EXPECT_EQ(woken, 1);
  job.cancel();
  EXPECT_EQ(woken, 2);
  EXPECT_TRUE(job.cancelled());
}
