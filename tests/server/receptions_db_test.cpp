// ListReceptions against a real PostgreSQL: what robots heard and did, as their agents log it
// (rows written here through a robot's store::Store, as dtmf-agent writes them), listed per
// robot and per run, and followed as each is stored.
#include <gtest/gtest.h>

#include <thread>

#include "db/temp_database.h"
#include "live_system.h"
#include "support/wait_for.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::LiveSystem;
using test_support::LiveSystemOptions;
using test_support::read_stream;
using test_support::wait_until;

namespace {

store::ReceptionRow heard(const std::string& event, int address, const std::string& command = "") {
  store::ReceptionRow r;
  r.host = "turtle";
  r.profile = "fast";
  r.heard_at = store::WallClock::now();
  r.crc_ok = !event.empty();
  r.event = event;
  r.reason = event == "refused" ? "authentication" : "";
  r.reply = event == "command" || event == "repeat" ? std::optional<std::string>("ack") : std::nullopt;
  r.command = command;
  r.robot_address = address;
  r.frame_width = 50;
  return r;
}

std::vector<v1::Reception> list(v1::TeleopService::Stub& client, v1::ListReceptionsRequest request,
                                grpc::Status* status = nullptr) {
  const auto result = read_stream<v1::ListReceptionsResponse>(
      [&](grpc::ClientContext& c) { return client.ListReceptions(&c, request); });
  if (status) *status = result.status;
  std::vector<v1::Reception> all;
  for (const auto& r : result.responses) all.push_back(r.reception());
  return all;
}

}  // namespace

TEST(ServerReceptions, ListsWhatTheRobotHeardAndDidOldestFirst) {
  test_support::TempDatabase db;
  LiveSystemOptions options;
  options.database = db.url();
  LiveSystem system(options);
  store::Store robot_log(store::StoreOptions{db.url(), ::testing::TempDir() + "/receptions.spill"});
  robot_log.write(heard("command", 0, "drive_for_duration speed=40.0% duration=1.03s"));
  robot_log.write(heard("repeat", 0));
  robot_log.write(heard("refused", 0));
  robot_log.write(heard("", 0));         // broken
  robot_log.write(heard("command", 5));  // another robot's
  ASSERT_TRUE(robot_log.flush(5s));
  auto client = system.client();
  v1::ListReceptionsRequest mine;
  mine.set_robot("robot");  // the server's one robot, at address 0
  const auto all = list(*client, mine);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].event(), "command");
  EXPECT_EQ(all[0].command(), "drive_for_duration speed=40.0% duration=1.03s");
  EXPECT_EQ(all[0].robot(), "robot");
  EXPECT_EQ(all[0].reply(), "ack");
  EXPECT_EQ(all[1].event(), "repeat");
  EXPECT_EQ(all[2].event(), "refused");
  EXPECT_EQ(all[2].reason(), "authentication");
  EXPECT_EQ(all[2].reply(), "");
  EXPECT_EQ(all[3].event(), "broken");
  EXPECT_FALSE(all[3].intact());
  EXPECT_LT(all[0].stored(), all[3].stored());
  EXPECT_EQ(list(*client, {}).size(), 5u) << "every robot's, none of ours among them too";
  v1::ListReceptionsRequest newest;
  newest.set_limit(2);
  const auto two = list(*client, newest);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[1].address(), 5u);
  EXPECT_EQ(two[1].robot(), "") << "address 5 is none of this server's robots";
}

TEST(ServerReceptions, FollowingGivesEachAsItIsStored) {
  test_support::TempDatabase db;
  LiveSystemOptions options;
  options.database = db.url();
  LiveSystem system(options);
  store::Store robot_log(store::StoreOptions{db.url(), ::testing::TempDir() + "/receptions-follow.spill"});
  robot_log.write(heard("command", 0, "stop"));
  ASSERT_TRUE(robot_log.flush(5s));
  auto client = system.client();
  grpc::ClientContext context;
  v1::ListReceptionsRequest follow;
  follow.set_follow(true);
  auto reader = client->ListReceptions(&context, follow);
  v1::ListReceptionsResponse m;
  ASSERT_TRUE(reader->Read(&m));
  EXPECT_EQ(m.reception().command(), "stop");
  const auto written = std::chrono::steady_clock::now();
  robot_log.write(heard("renewal", 0));
  ASSERT_TRUE(robot_log.flush(5s));
  ASSERT_TRUE(reader->Read(&m));
  EXPECT_EQ(m.reception().event(), "renewal");
  std::printf("a reception stored to its follower: %.0f ms\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - written).count());
  context.TryCancel();
  while (reader->Read(&m)) {
  }
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::CANCELLED);
}

TEST(ServerReceptions, RefusesWhatIsNotThere) {
  test_support::TempDatabase db;
  LiveSystemOptions options;
  options.database = db.url();
  LiveSystem system(options);
  auto client = system.client();
  grpc::Status status;
  v1::ListReceptionsRequest request;
  request.set_robot("nobody");
  list(*client, request, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << status.error_message();
  request.set_robot("");
  request.set_run_number(42);
  list(*client, request, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << status.error_message();
  request.clear_run_number();
  request.set_limit(10001);
  list(*client, request, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  LiveSystem without;  // --db none
  auto other = without.client();
  list(*other, {}, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION) << status.error_message();
}
