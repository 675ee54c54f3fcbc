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
  EXPECT_EQ(job.await_decision(), std::nullopt);  // and it was not kept for later
}

TEST(Job, ADecisionRightAfterTheQuestionOpensIsKeptUntilTheTransmitterWaits) {
  auto job = reset_job(std::chrono::seconds(60));
  job.open_decision();
  EXPECT_TRUE(job.decide(reliability::Decision::Retransmit));
  EXPECT_FALSE(job.decide(reliability::Decision::Continue));  // one answer per question
  EXPECT_EQ(job.await_decision(), reliability::Decision::Retransmit);
}

TEST(Job, AQuestionNobodyAnswersTimesOutAndCloses) {
  auto job = reset_job(std::chrono::milliseconds(10));
  job.open_decision();
  EXPECT_EQ(job.await_decision(), std::nullopt);
  EXPECT_FALSE(job.decide(reliability::Decision::Continue));
}
