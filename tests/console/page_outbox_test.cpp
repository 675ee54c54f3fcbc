// What waits to go to a page (clients/console/page_outbox.h): a slow page loses columns, oldest
// first, and is told; what may not be lost closes the page rather than grow without bound.
#include "page_outbox.h"

#include <gtest/gtest.h>

#include <thread>

using dtmf::console::PageOutbox;

TEST(PageOutbox, TextsGoOutInOrder) {
  PageOutbox box(1000);
  ASSERT_TRUE(box.put("a", false));
  ASSERT_TRUE(box.put("b", true));
  EXPECT_EQ(box.take(), "a");
  EXPECT_EQ(box.take(), "b");
}

TEST(PageOutbox, ASlowPageLosesTheOldestColumnsAndIsToldHowMany) {
  PageOutbox box(100);
  ASSERT_TRUE(box.put("event-1", false));
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(box.put("column-" + std::string(20, char('0' + i)), true));
  // 7 + 10 × 27 bytes against 100: the oldest seven columns went.
  EXPECT_EQ(box.dropped_columns(), 7u);
  EXPECT_EQ(box.take(), R"({"dropped_columns":7})");
  EXPECT_EQ(box.take(), "event-1") << "events are never dropped for columns";
  EXPECT_EQ(box.take(), "column-" + std::string(20, '7'));
}

TEST(PageOutbox, WhatMayNotBeLostOverflowsAndClosesThePage) {
  PageOutbox box(10);
  ASSERT_TRUE(box.put("12345", false));
  EXPECT_FALSE(box.put("678901", false));
  EXPECT_EQ(box.take(), std::nullopt) << "the page is closed, not sent a part";
  EXPECT_FALSE(box.put("x", true));
}

TEST(PageOutbox, ShuttingWakesTheWriter) {
  PageOutbox box;
  std::optional<std::string> taken = "not yet";
  std::thread writer([&] { taken = box.take(); });
  box.shut();
  writer.join();
  EXPECT_EQ(taken, std::nullopt);
}
