// dtmf-server --robots FILE: the robots file read, and every mistake in it named.
#include "robot_roster.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using dtmf::server::parse_robots;

TEST(RobotRoster, ReadsEachRobotsNameAddressKeyAndModel) {
  const auto robots = parse_robots(R"([{"name": "alpha", "address": 1, "key": "/k/alpha.key", "model": "waffle"},
                                       {"name": "beta-2", "address": 7}])",
                                   "robots.json");
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0].name, "alpha");
  EXPECT_EQ(robots[0].address, 1);
  EXPECT_EQ(robots[0].key_file, "/k/alpha.key");
  EXPECT_EQ(robots[0].model, "waffle");
  EXPECT_EQ(robots[1].name, "beta-2");
  EXPECT_EQ(robots[1].address, 7);
  EXPECT_EQ(robots[1].key_file, "");
  EXPECT_EQ(robots[1].model, "burger");
}

TEST(RobotRoster, EveryMistakeIsNamedWithTheFileTheRobotAndTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {"not json", "not JSON"},
      {R"({"name": "alpha"})", "not a list"},
      {"[]", "lists no robot"},
      {R"([{"address": 1}])", "robot 1: \"name\" is required"},
      {R"([{"name": "al pha", "address": 1}])", "name \"al pha\""},
      {R"([{"name": "alpha"}])", "robot 1 (alpha): \"address\" is required"},
      {R"([{"name": "alpha", "address": 8}])", "address 8 is outside 0..7"},
      {R"([{"name": "alpha", "address": -1}])", "address -1 is outside 0..7"},
      {R"([{"name": "alpha", "address": 1.5}])", "\"address\" is required, a whole number"},
      {R"([{"name": "alpha", "address": 1, "model": "tank"}])", "unknown robot model 'tank'"},
      {R"([{"name": "alpha", "address": 1, "key": ""}])", "\"key\" is the path"},
      {R"([{"name": "alpha", "address": 1, "adress": 2}])", "unknown field \"adress\""},
      {R"([{"name": "a", "address": 1}, {"name": "a", "address": 2}])", "two robots are called a"},
      {R"([{"name": "a", "address": 1}, {"name": "b", "address": 1}])", "robots a and b share address 1"},
  };
  for (const auto& [json, expected] : cases) {
    try {
      parse_robots(json, "robots.json");
      ADD_FAILURE() << "accepted " << json;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("robots.json", 0), 0u) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << json << " -> " << what;
    }
  }
}
