// DdsCmdVel against a ROS 2-like subscriber in the same process, over loopback only: what
// arrives (values, order, header stamp), the DDS names ROS 2 matches on, where the domain
// comes from, and what a failure to start says.
#include "cmd_vel/dds_cmd_vel.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "agent/dds_test_subscriber.h"

namespace dtmf::agent {
namespace {

using namespace std::chrono_literals;
using test_support::CmdVelSubscriber;

constexpr auto kMatchTimeout = 3s;
constexpr auto kReceiveTimeout = 3s;

// Each test process gets its own domain and topic names, so tests run in parallel never see
// each other's samples. 100-199 (and the next two, which some tests use) stay clear of 0
// and of TurtleBot3's 30, in case the tests ever run on the robot itself.
int test_domain() { return 100 + static_cast<int>(getpid() % 100); }
std::string unique_topic(const std::string& name) { return name + "_" + std::to_string(getpid()); }

// Sets an environment variable for one scope, restoring what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

class DdsCmdVelTest : public ::testing::Test {
 protected:
  // CycloneDDS reads its configuration when a process first joins a domain: loopback only,
  // so that tests neither need a network nor reach a real robot.
  static void SetUpTestSuite() {
    setenv("CYCLONEDDS_URI", R"(<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>)", 1);
  }
};

std::chrono::system_clock::time_point stamp_at(std::int64_t sec, std::int64_t nanosec) {
  return std::chrono::system_clock::time_point(std::chrono::duration_cast<std::chrono::system_clock::duration>(
      std::chrono::seconds(sec) + std::chrono::nanoseconds(nanosec)));
}

// Designated initializers would be shorter, but GCC 12 warns on every field left out.
DdsOptions options(const std::string& topic, std::optional<int> domain_id, bool stamped = true) {
  DdsOptions o;
  o.topic = topic;
  o.stamped = stamped;
  o.domain_id = domain_id;
  return o;
}

const Velocity kVelocities[] = {{0.1, 0.0}, {0.22, -0.5}, {0.0, 2.84}, {-0.15, 1.25}, {0.0, 0.0}};

TEST_F(DdsCmdVelTest, TwistStampedArrivesInOrderWithItsStamp) {
  const std::string topic = unique_topic("cmd_vel_stamped");
  CmdVelSubscriber subscriber(test_domain(), "rt/" + topic, /*stamped=*/true);
  DdsOptions o = options("/" + topic, test_domain());
  o.frame_id = "base_link";
  DdsCmdVel publisher(o);
  EXPECT_EQ(publisher.type_name(), "geometry_msgs::msg::dds_::TwistStamped_");
  EXPECT_EQ(publisher.topic_name(), "rt/" + topic);
  ASSERT_TRUE(publisher.wait_for_subscribers(1, kMatchTimeout));
  EXPECT_EQ(publisher.matched_subscribers(), 1);
  EXPECT_EQ(subscriber.matched_publishers(), 1);

  for (int i = 0; i < 5; ++i) {
    publisher.publish(kVelocities[i], 1000.0 * i, stamp_at(1'700'000'000 + i, 123'456'789 + i));
  }
  ASSERT_TRUE(subscriber.wait_for(5, kReceiveTimeout));

  const auto samples = subscriber.samples();
  ASSERT_EQ(samples.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(samples[i].linear.x, kVelocities[i].linear_mps);
    EXPECT_EQ(samples[i].angular.z, kVelocities[i].angular_radps);
    EXPECT_TRUE(samples[i].from_agent) << "the writer carries the agent's user data (the ROS 2 bridge skips it)";
    EXPECT_EQ(samples[i].linear.y, 0);
    EXPECT_EQ(samples[i].linear.z, 0);
    EXPECT_EQ(samples[i].angular.x, 0);
    EXPECT_EQ(samples[i].angular.y, 0);
    EXPECT_EQ(samples[i].stamp_sec, 1'700'000'000 + i);
    EXPECT_EQ(samples[i].stamp_nanosec, 123'456'789u + i);
    EXPECT_EQ(samples[i].frame_id, "base_link");
  }
}

TEST_F(DdsCmdVelTest, StampBefore1970KeepsNanosecPositive) {
  const std::string topic = unique_topic("cmd_vel_negative_stamp");
  CmdVelSubscriber subscriber(test_domain(), "rt/" + topic, /*stamped=*/true);
  DdsCmdVel publisher(options(topic, test_domain()));
  ASSERT_TRUE(publisher.wait_for_subscribers(1, kMatchTimeout));

  publisher.publish({0.1, 0.2}, 0, stamp_at(0, -250'000'000));  // 1969-12-31T23:59:59.75
  ASSERT_TRUE(subscriber.wait_for(1, kReceiveTimeout));
  EXPECT_EQ(subscriber.samples()[0].stamp_sec, -1);
  EXPECT_EQ(subscriber.samples()[0].stamp_nanosec, 750'000'000u);
}

TEST_F(DdsCmdVelTest, TwistArrivesInOrder) {
  const std::string topic = unique_topic("cmd_vel_twist");
  CmdVelSubscriber subscriber(test_domain(), "rt/" + topic, /*stamped=*/false);
  DdsCmdVel publisher(options(topic, test_domain(), /*stamped=*/false));
  EXPECT_EQ(publisher.type_name(), "geometry_msgs::msg::dds_::Twist_");
  ASSERT_TRUE(publisher.wait_for_subscribers(1, kMatchTimeout));

  for (int i = 0; i < 5; ++i) publisher.publish(kVelocities[i], 1000.0 * i, std::chrono::system_clock::now());
  ASSERT_TRUE(subscriber.wait_for(5, kReceiveTimeout));

  const auto samples = subscriber.samples();
  ASSERT_EQ(samples.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(samples[i].linear.x, kVelocities[i].linear_mps);
    EXPECT_EQ(samples[i].angular.z, kVelocities[i].angular_radps);
    EXPECT_EQ(samples[i].linear.y, 0);
    EXPECT_EQ(samples[i].angular.x, 0);
  }
}

// Different types on one topic name are different DDS topics to ROS 2: a Twist writer
// must not match a TwistStamped reader (as a Humble-style agent meets a Jazzy TurtleBot3).
TEST_F(DdsCmdVelTest, TwistDoesNotMatchTwistStampedSubscriber) {
  const std::string topic = unique_topic("cmd_vel_mismatch");
  CmdVelSubscriber subscriber(test_domain(), "rt/" + topic, /*stamped=*/true);
  DdsCmdVel publisher(options(topic, test_domain(), /*stamped=*/false));
  EXPECT_FALSE(publisher.wait_for_subscribers(1, 200ms));
  EXPECT_EQ(publisher.matched_subscribers(), 0);
}

TEST_F(DdsCmdVelTest, NoSubscriberMeansWaitTimesOut) {
  DdsCmdVel publisher(options(unique_topic("cmd_vel_nobody"), test_domain()));
  EXPECT_EQ(publisher.matched_subscribers(), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(publisher.wait_for_subscribers(1, 100ms));
  EXPECT_GE(std::chrono::steady_clock::now() - start, 100ms);
  publisher.publish({0.1, 0}, 0, std::chrono::system_clock::now());  // nobody listening is no error
}

TEST(DdsTopicName, RosNamesGetTheRtPrefix) {
  EXPECT_EQ(dds_topic_name("cmd_vel"), "rt/cmd_vel");
  EXPECT_EQ(dds_topic_name("/cmd_vel"), "rt/cmd_vel");
  EXPECT_EQ(dds_topic_name("/robot1/cmd_vel"), "rt/robot1/cmd_vel");
  EXPECT_THROW(dds_topic_name(""), DdsError);
  EXPECT_THROW(dds_topic_name("/"), DdsError);
}

TEST_F(DdsCmdVelTest, TopicWithAndWithoutSlashIsRtCmdVel) {
  DdsCmdVel with_slash(options("/cmd_vel", test_domain()));
  DdsCmdVel without_slash(options("cmd_vel", test_domain()));
  DdsOptions defaults;
  defaults.domain_id = test_domain();
  DdsCmdVel by_default(defaults);
  EXPECT_EQ(with_slash.topic_name(), "rt/cmd_vel");
  EXPECT_EQ(without_slash.topic_name(), "rt/cmd_vel");
  EXPECT_EQ(by_default.topic_name(), "rt/cmd_vel");
  EXPECT_EQ(by_default.type_name(), "geometry_msgs::msg::dds_::TwistStamped_");
}

TEST_F(DdsCmdVelTest, DomainComesFromRosDomainIdWhenNotGiven) {
  const int domain = test_domain() + 1;
  const ScopedEnv env("ROS_DOMAIN_ID", std::to_string(domain).c_str());
  const std::string topic = unique_topic("cmd_vel_env_domain");
  CmdVelSubscriber subscriber(domain, "rt/" + topic, /*stamped=*/true);
  DdsCmdVel publisher(options(topic, std::nullopt));
  EXPECT_EQ(publisher.domain_id(), domain);
  ASSERT_TRUE(publisher.wait_for_subscribers(1, kMatchTimeout));
  publisher.publish({0.2, 0.3}, 0, std::chrono::system_clock::now());
  ASSERT_TRUE(subscriber.wait_for(1, kReceiveTimeout));
  EXPECT_EQ(subscriber.samples()[0].linear.x, 0.2);

  DdsCmdVel given(options(topic, test_domain()));
  EXPECT_EQ(given.domain_id(), test_domain());
}

TEST_F(DdsCmdVelTest, DomainIsZeroWithoutRosDomainId) {
  const ScopedEnv env("ROS_DOMAIN_ID", nullptr);
  DdsCmdVel publisher(options(unique_topic("cmd_vel_domain0"), std::nullopt));
  EXPECT_EQ(publisher.domain_id(), 0);
}

TEST_F(DdsCmdVelTest, BadRosDomainIdIsAnError) {
  const ScopedEnv env("ROS_DOMAIN_ID", "thirty");
  try {
    DdsCmdVel publisher(options(unique_topic("cmd_vel"), std::nullopt));
    FAIL() << "no error";
  } catch (const DdsError& e) {
    EXPECT_NE(std::string(e.what()).find("ROS_DOMAIN_ID=\"thirty\""), std::string::npos) << e.what();
  }
}

// Cyclone itself says only "Error" (and logs the port numbers on stderr): the message
// must explain.
TEST_F(DdsCmdVelTest, DomainOutOfRangeSaysWhy) {
  try {
    DdsCmdVel publisher(options(unique_topic("cmd_vel"), 300));
    FAIL() << "no error";
  } catch (const DdsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("participant on domain 300"), std::string::npos) << what;
    EXPECT_NE(what.find("failed: Error"), std::string::npos) << what;
    EXPECT_NE(what.find("65535"), std::string::npos) << what;
    EXPECT_NE(what.find("CYCLONEDDS_URI"), std::string::npos) << what;
    EXPECT_LT(e.retcode(), 0);
  }
}

// Cast to a DDS domain id, -1 would be DDS_DOMAIN_DEFAULT and silently join domain 0.
TEST_F(DdsCmdVelTest, NegativeDomainIsAnError) {
  EXPECT_THROW(DdsCmdVel(options(unique_topic("cmd_vel"), -1)), DdsError);
}

TEST_F(DdsCmdVelTest, MissingNetworkInterfaceNamesCycloneddsUri) {
  // A domain no other test joins: the configuration is read when the process first joins it.
  const ScopedEnv uri("CYCLONEDDS_URI",
                      R"(<General><Interfaces><NetworkInterface name="no-such-if0"/></Interfaces></General>)");
  try {
    DdsCmdVel publisher(options(unique_topic("cmd_vel"), test_domain() + 2));
    FAIL() << "no error";
  } catch (const DdsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("participant"), std::string::npos) << what;
    EXPECT_NE(what.find("CYCLONEDDS_URI"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace dtmf::agent
