// The bridge's topics: cmd_vel for one robot, ROBOT/cmd_vel for several.
#include "bridge_topics.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace dtmf::ros_bridge {
namespace {

TEST(BridgeTopics, OneRobotListensOnCmdVelAsTheToolsPublishByDefault) {
  const BridgeTopics t = bridge_topics({"robot"});
  ASSERT_EQ(t.robots.size(), 1u);
  EXPECT_EQ(t.robots[0].cmd_vel, "cmd_vel");
  EXPECT_EQ(t.robots[0].cmd_vel_confirmed, "cmd_vel_confirmed");
  EXPECT_EQ(t.stop_every_robot, "stop_every_robot");
  EXPECT_EQ(t.diagnostics, "diagnostics");
}

TEST(BridgeTopics, SeveralRobotsAreNamespacedByTheirNames) {
  const BridgeTopics t = bridge_topics({"robot1", "robot2", "robot3"});
  ASSERT_EQ(t.robots.size(), 3u);
  EXPECT_EQ(t.robots[1].robot, "robot2");
  EXPECT_EQ(t.robots[1].cmd_vel, "robot2/cmd_vel");
  EXPECT_EQ(t.robots[2].cmd_vel_confirmed, "robot3/cmd_vel_confirmed");
}

TEST(BridgeTopics, ANameThatCannotBeANamespaceIsRefusedQuotedAndBounded) {
  try {
    bridge_topics({"robot1", "bad name\n" + std::string(200, 'x')});
    FAIL() << "a name with a space and a newline was taken";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"bad name?xxx"), std::string::npos) << what;
    EXPECT_LT(what.size(), 250u) << "the name is bounded";
  }
  EXPECT_THROW(bridge_topics({"robot1", "2robot"}), std::invalid_argument);
  EXPECT_THROW(bridge_topics({}), std::invalid_argument);
}

}  // namespace
}  // namespace dtmf::ros_bridge
