// The link's health as /diagnostics reports it: OK, WARN when answers are lost, ERROR when
// the robot stopped answering.
#include "link_health.h"

#include <gtest/gtest.h>

namespace dtmf::ros_bridge {
namespace {

LinkReading answered(double quality, unsigned frames) {
  LinkReading r;
  r.answered = true;
  r.link_quality = quality;
  r.frames_in_window = frames;
  r.window_s = 5;
  return r;
}

LinkReading unanswered(double quality, unsigned frames) {
  LinkReading r = answered(quality, frames);
  r.answered = false;
  r.unanswered = true;
  return r;
}

std::string value_of(const HealthReport& report, const std::string& key) {
  for (const auto& [k, v] : report.values)
    if (k == key) return v;
  return "(none)";
}

TEST(LinkHealth, OkBeforeAnyFrameAndWhileEveryFrameIsAnswered) {
  LinkHealth health;
  EXPECT_EQ(health.report(StreamState::Closed, 0).level, HealthLevel::Ok);
  EXPECT_EQ(value_of(health.report(StreamState::Closed, 0), "last answer s ago"), "never");
  health.on_reading(answered(1.0, 10), 1000);
  const HealthReport r = health.report(StreamState::Open, 1500);
  EXPECT_EQ(r.level, HealthLevel::Ok);
  EXPECT_EQ(r.message, "answering: 10 of 10 frames answered in the last 5 s");
  EXPECT_EQ(value_of(r, "last answer s ago"), "0.5");
  EXPECT_EQ(value_of(r, "stream"), "open");
}

TEST(LinkHealth, WarnWhenAnswersAreLostAndOkAgainOnceTheWindowIsClean) {
  LinkHealth health;
  health.on_reading(unanswered(0.8, 10), 0);
  health.on_reading(answered(0.8, 10), 100);
  HealthReport r = health.report(StreamState::Open, 100);
  EXPECT_EQ(r.level, HealthLevel::Warn);
  EXPECT_EQ(r.message, "answers lost: 8 of 10 frames answered in the last 5 s");
  health.on_reading(answered(1.0, 10), 6000);
  EXPECT_EQ(health.report(StreamState::Open, 6000).level, HealthLevel::Ok);
}

TEST(LinkHealth, AWindowWithNoEndedFrameIsNoLoss) {
  LinkHealth health;
  LinkReading first;  // a stream's first response: the server's window is empty, its quality 0
  first.link_quality = 0;
  first.window_s = 3;
  health.on_reading(first, 0);
  const HealthReport r = health.report(StreamState::Open, 0);
  EXPECT_EQ(r.level, HealthLevel::Ok);
  EXPECT_EQ(r.message, "no frame ended in the last 3 s");
}

TEST(LinkHealth, ErrorAfterThreeUnansweredFramesInARow) {
  LinkHealth health;
  health.on_reading(answered(1.0, 5), 0);
  health.on_reading(unanswered(0.8, 5), 100);
  health.on_reading(unanswered(0.6, 5), 200);
  EXPECT_EQ(health.report(StreamState::Open, 200).level, HealthLevel::Warn);
  health.on_reading(unanswered(0.4, 5), 300);
  const HealthReport r = health.report(StreamState::Open, 300);
  EXPECT_EQ(r.level, HealthLevel::Error);
  EXPECT_EQ(r.message, "not answering: the last 3 frames unanswered");
  health.on_reading(answered(0.5, 6), 400);
  EXPECT_EQ(health.report(StreamState::Open, 400).level, HealthLevel::Warn) << "an answer ends the error";
}

TEST(LinkHealth, BetweenDrivesTheLastMeasurementIsKeptAndSaidToBeOld) {
  LinkHealth health;
  health.on_reading(answered(0.5, 4), 1000);
  const HealthReport r = health.report(StreamState::Closed, 4000);
  EXPECT_EQ(r.level, HealthLevel::Warn);
  EXPECT_NE(r.message.find("measured 3.0 s ago; not driving now"), std::string::npos) << r.message;
  EXPECT_EQ(value_of(r, "lease left s"), "0.00");
}

}  // namespace
}  // namespace dtmf::ros_bridge
