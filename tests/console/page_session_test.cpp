// A page's calls relayed to a real server (clients/console/page_session.h): the in-process
// system of the server tests (gRPC on loopback, the transmitter, a simulated room, the robot
// agent), and the page's JSON as the browser sends it. No browser: tests/console/ drives one.
#include "page_session.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "live_system.h"
#include "support/wait_for.h"

using namespace dtmf;
using namespace std::chrono_literals;
using nlohmann::json;
using test_support::LiveSystem;
using test_support::wait_until;

namespace {

// A page: its session, and what the console sent it, read as the page's writer would.
class Page {
 public:
  explicit Page(LiveSystem& system, const std::string& client = "test page")
      : outbox_(std::make_shared<console::PageOutbox>()) {
    console::ServerLink link;
    link.stub = std::make_shared<grpc::GenericStub>(system.channel());
    link.address = "in-process";
    link.context = [](const std::string& name) {
      auto c = std::make_unique<grpc::ClientContext>();
      c->AddMetadata("x-dtmf-client", name);
      return c;
    };
    session_ = std::make_shared<console::PageSession>(link, client, outbox_);
    reader_ = std::thread([this] {
      while (auto text = outbox_->take()) {
        std::lock_guard lock(mutex_);
        heard_.push_back(json::parse(*text));
      }
    });
  }
  ~Page() {
    session_.reset();
    outbox_->shut();
    reader_.join();
  }

  void say(const std::string& text) { session_->hear(text); }
  void say(const json& message) { session_->hear(message.dump()); }

  // The first message that `match` accepts, waiting up to `within`.
  std::optional<json> heard(const std::function<bool(const json&)>& match, std::chrono::milliseconds within = 5s) {
    std::optional<json> found;
    wait_until(
        [&] {
          std::lock_guard lock(mutex_);
          for (const auto& m : heard_)
            if (match(m)) return (found = m).has_value();
          return false;
        },
        within);
    return found;
  }
  std::optional<json> status_of(int call, std::chrono::milliseconds within = 5s) {
    const auto m = heard([&](const json& j) { return j.value("call", 0) == call && j.contains("status"); }, within);
    return m ? std::optional(m->at("status")) : std::nullopt;
  }
  std::vector<json> messages_of(int call) {
    std::lock_guard lock(mutex_);
    std::vector<json> out;
    for (const auto& m : heard_)
      if (m.value("call", 0) == call && m.contains("message")) out.push_back(m["message"]);
    return out;
  }

 private:
  std::shared_ptr<console::PageOutbox> outbox_;
  std::shared_ptr<console::PageSession> session_;
  std::mutex mutex_;
  std::vector<json> heard_;
  std::thread reader_;
};

}  // namespace

TEST(ConsolePage, ADriveIsRelayedWithItsProgressAndItsStatus) {
  LiveSystem system;
  Page page(system);
  ASSERT_TRUE(page.heard([](const json& m) { return m.contains("hello"); }));
  page.say(json{{"open", 1},
                {"method", "Drive"},
                {"request", {{"speed_percent", 40}, {"duration_s", 1}, {"options", {{"profile", "fast"}}}}}});
  const auto status = page.status_of(1, 10s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status->at("name"), "OK") << status->dump();
  bool confirmed = false;
  for (const auto& m : page.messages_of(1)) confirmed = confirmed || m["progress"]["event"] == "FRAME_EVENT_CONFIRMED";
  EXPECT_TRUE(confirmed) << "the progress the server streamed reached the page";
  EXPECT_GT(system.last_velocity().linear_mps, 0.0);
}

TEST(ConsolePage, TheServersOwnRulesJudgeEveryRequest) {
  LiveSystem system;
  Page page(system);
  page.say(json{{"open", 1}, {"method", "Drive"}, {"request", {{"speed_percent", 400}}}});
  auto status = page.status_of(1);
  ASSERT_TRUE(status);
  EXPECT_EQ(status->at("name"), "INVALID_ARGUMENT");
  EXPECT_NE(status->at("message").get<std::string>().find("speed"), std::string::npos) << status->dump();

  page.say(json{{"open", 2}, {"method", "Drive"}, {"request", {{"sped_percent", 40}}}});
  status = page.status_of(2);
  ASSERT_TRUE(status);
  EXPECT_EQ(status->at("name"), "INVALID_ARGUMENT");
  EXPECT_NE(status->at("message").get<std::string>().find("sped_percent"), std::string::npos) << status->dump();
  EXPECT_EQ(system.last_velocity().linear_mps, 0.0) << "nothing drove";
}

TEST(ConsolePage, WhatIsNotAPagesMessageIsAnsweredWithAnErrorNamingIt) {
  LiveSystem system;
  Page page(system);
  const auto error_with = [&](const std::string& part) {
    return page.heard([&](const json& m) {
      return m.contains("error") && m["error"].get<std::string>().find(part) != std::string::npos;
    });
  };
  page.say(std::string("not json\n\x1b[2J"));
  EXPECT_TRUE(error_with("not a JSON object: \"not json\\n\\x1b[2J\""));
  page.say(json{{"open", 1}, {"method", "FormatDisk"}, {"request", json::object()}});
  EXPECT_TRUE(error_with("no method \"FormatDisk\""));
  page.say(json{{"open", 0}, {"method", "Drive"}, {"request", json::object()}});
  EXPECT_TRUE(error_with("a positive call ID"));
  page.say(std::string(20 * 1024, ' '));
  EXPECT_TRUE(error_with("at most 16384"));
  page.say(json{{"open", 5}, {"method", "ListRobots"}, {"request", json::object()}});
  ASSERT_TRUE(page.status_of(5));
  page.say(json{{"open", 4}, {"method", "ListRobots"}, {"request", json::object()}});
  EXPECT_TRUE(error_with("IDs must grow"));
}

TEST(ConsolePage, ATeleopStreamTakesTargetsAndEndsWhenThePageCloses) {
  LiveSystem system;
  Page page(system, "console page 1 (127.0.0.1)");
  page.say(json{{"open", 1},
                {"method", "Teleop"},
                {"request", {{"linear_mps", 0.05}, {"lease_s", 0.5}, {"options", {{"profile", "fast"}}}}}});
  ASSERT_TRUE(wait_until([&] { return system.last_velocity().linear_mps > 0.04; }, 5s));
  page.say(json{{"send", 1}, {"request", {{"linear_mps", 0.1}, {"lease_s", 0.5}}}});
  ASSERT_TRUE(wait_until([&] { return system.last_velocity().linear_mps > 0.09; }, 5s));

  // Another page is refused, and told who drives.
  {
    Page other(system, "console page 2 (127.0.0.1)");
    other.say(json{
        {"open", 1}, {"method", "Teleop"}, {"request", {{"linear_mps", 0.02}, {"options", {{"profile", "fast"}}}}}});
    const auto refused = other.status_of(1);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->at("name"), "FAILED_PRECONDITION");
    EXPECT_NE(refused->at("message").get<std::string>().find("held by \"console page 1 (127.0.0.1)\""),
              std::string::npos)
        << refused->dump();
  }
  page.say(json{{"close", 1}});
  const auto ended = page.status_of(1);
  ASSERT_TRUE(ended);
  EXPECT_EQ(ended->at("name"), "OK") << ended->dump();
  EXPECT_TRUE(wait_until([&] { return system.last_velocity() == agent::Velocity{}; }, 3s))
      << "the lease lapsed and the robot stopped";
}

TEST(ConsolePage, APageThatGoesAwayCancelsItsCalls) {
  LiveSystem system;
  {
    Page page(system);
    page.say(json{{"open", 1},
                  {"method", "Teleop"},
                  {"request", {{"linear_mps", 0.05}, {"lease_s", 0.5}, {"options", {{"profile", "fast"}}}}}});
    ASSERT_TRUE(wait_until([&] { return system.last_velocity().linear_mps > 0.04; }, 5s));
  }  // the tab closed
  EXPECT_TRUE(wait_until([&] { return system.last_velocity() == agent::Velocity{}; }, 3s))
      << "the robot stopped within its lease";
  Page next(system);
  next.say(json{{"open", 1},
                {"method", "Teleop"},
                {"request", {{"linear_mps", 0.02}, {"lease_s", 0.5}, {"options", {{"profile", "fast"}}}}}});
  EXPECT_TRUE(wait_until([&] { return system.last_velocity().linear_mps > 0.01; }, 5s)) << "the robot is free";
}
