// The air's fan-out (server/air_fanout.h): a slow watcher loses its oldest entries and is told
// how many; columns go before events; each watcher gets its robot's events and its own rate
// and resolution of columns; publishing never waits.
#include "air_fanout.h"

#include <gtest/gtest.h>

#include <atomic>

using namespace dtmf::server;

namespace {

AirEvent frame_for(const std::string& robot, double audio_ms) {
  FramePlayed played;
  played.command_id = "c" + std::to_string(static_cast<int>(audio_ms));
  if (!robot.empty()) played.robots.push_back(robot);
  return AirEvent{audio_ms, {}, played};
}

SpectrumColumn full_column() {
  SpectrumColumn c{1000, 19000.0 / kMaxColumnBins, 42.7, std::vector<float>(kMaxColumnBins, -100.0f)};
  c.level_dbfs[100] = -10;
  return c;
}

}  // namespace

TEST(AirFanout, ASlowWatcherLosesItsOldestAndIsToldHowMany) {
  AirFanout fanout;
  WatchOptions options;
  options.max_events = 4;
  const auto slow = fanout.watch(options);
  ASSERT_TRUE(slow);
  for (int i = 0; i < 10; ++i) fanout.publish(frame_for("alpha", i));
  auto first = fanout.take(*slow);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->dropped_events, 6u);
  EXPECT_EQ(first->event.audio_ms, 6);  // the newest four are kept
  for (int expected = 7; expected < 10; ++expected) {
    auto next = fanout.take(*slow);
    ASSERT_TRUE(next);
    EXPECT_EQ(next->dropped_events, 0u);  // told once
    EXPECT_EQ(next->event.audio_ms, expected);
  }
  EXPECT_FALSE(fanout.take(*slow));
}

TEST(AirFanout, AWatcherOfOneRobotSeesItsEventsAndTheRooms) {
  AirFanout fanout;
  WatchOptions options;
  options.robot = "beta";
  const auto beta = fanout.watch(options);
  const auto all = fanout.watch({});
  fanout.publish(frame_for("alpha", 1));
  fanout.publish(frame_for("beta", 2));
  fanout.publish(frame_for("", 3));  // a stop for every robot
  fanout.publish(AirEvent{4, {}, AirBusy{true, -30, -60}});
  fanout.publish(AirEvent{5, {}, AnswerHeard{"alpha", "fast", true, 3, false, 0, -20}});
  std::vector<double> seen;
  while (auto e = fanout.take(*beta)) seen.push_back(e->event.audio_ms);
  EXPECT_EQ(seen, (std::vector<double>{2, 3, 4}));
  int every = 0;
  while (fanout.take(*all)) ++every;
  EXPECT_EQ(every, 5);
}

TEST(AirFanout, ColumnsComeAtEachWatchersRateAndResolutionBehindItsEvents) {
  AirFanout fanout;
  WatchOptions slow_columns;
  slow_columns.spectrum = true;
  slow_columns.columns_per_s = 10;
  slow_columns.bins = 64;
  slow_columns.max_columns = 100;
  const auto watcher = fanout.watch(slow_columns);
  const auto events_only = fanout.watch({});
  EXPECT_TRUE(fanout.spectrum_watched());
  for (int i = 0; i < 50; ++i) fanout.publish_column(20.0 * i, {}, full_column());  // 1 s at 50 a second
  fanout.publish(frame_for("alpha", 999));
  auto first = fanout.take(*watcher);
  ASSERT_TRUE(first);
  EXPECT_TRUE(std::holds_alternative<FramePlayed>(first->event.what));  // the event first
  int columns = 0;
  while (auto c = fanout.take(*watcher)) {
    const auto& column = std::get<SpectrumColumn>(c->event.what);
    ASSERT_EQ(column.level_dbfs.size(), 64u);
    EXPECT_NEAR(column.step_hz, 19000.0 / 64, 1e-9);
    EXPECT_EQ(column.level_dbfs[100 * 64 / kMaxColumnBins], -10);  // the loudest bin survives the merge
    ++columns;
  }
  EXPECT_EQ(columns, 10);
  auto only = fanout.take(*events_only);
  ASSERT_TRUE(only);
  EXPECT_FALSE(fanout.take(*events_only));  // no columns for one who did not ask
  fanout.unwatch(watcher);
  EXPECT_FALSE(fanout.spectrum_watched());
}

TEST(AirFanout, ColumnsAreLostBeforeEvents) {
  AirFanout fanout;
  WatchOptions options;
  options.spectrum = true;
  options.columns_per_s = kMaxColumnsPerS;
  options.max_columns = 5;
  const auto watcher = fanout.watch(options);
  for (int i = 0; i < 30; ++i) {
    fanout.publish_column(20.0 * i, {}, full_column());
    if (i % 10 == 0) fanout.publish(frame_for("alpha", 20.0 * i));
  }
  auto first = fanout.take(*watcher);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->dropped_events, 0u);
  EXPECT_EQ(first->dropped_columns, 25u);
  int events = 1;
  while (auto e = fanout.take(*watcher))
    if (std::holds_alternative<FramePlayed>(e->event.what)) ++events;
  EXPECT_EQ(events, 3);
}

TEST(AirFanout, TheReadyCallbackMayTakeAtOnce) {
  AirFanout fanout;
  const auto watcher = fanout.watch({});
  std::atomic<int> taken{0};
  // Called after the fan-out's lock is let go: taking from it there does not deadlock.
  fanout.on_ready(watcher, [&] {
    while (fanout.take(*watcher)) ++taken;
  });
  for (int i = 0; i < 3; ++i) fanout.publish(frame_for("alpha", i));
  EXPECT_EQ(taken, 3);
  fanout.close();
  EXPECT_TRUE(fanout.closed());
  EXPECT_FALSE(fanout.watch({}));  // closed: no new watcher
}

TEST(AirFanout, WatchersAreCappedAndOptionsChecked) {
  AirFanout fanout;
  std::vector<std::shared_ptr<AirWatch>> watchers;
  for (std::size_t i = 0; i < kMaxWatchers; ++i) watchers.push_back(fanout.watch({}));
  EXPECT_FALSE(fanout.watch({}));
  fanout.unwatch(watchers.back());
  EXPECT_TRUE(fanout.watch({}));
  WatchOptions fast;
  fast.spectrum = true;
  fast.columns_per_s = kMaxColumnsPerS + 1;
  EXPECT_THROW(fanout.watch(fast), std::invalid_argument);
  WatchOptions fine;
  fine.spectrum = true;
  fine.bins = kMaxColumnBins + 1;
  EXPECT_THROW(fanout.watch(fine), std::invalid_argument);
}
