// TeleopService::ListReceptions: what robots heard and did, read through the store
// (store::ReceptionReader, ReceptionFeed: the SQL is the store's). Following, it waits on the
// database's announcement of each stored reception, not on a timer; the wait is cut short
// every kCancelCheck only to see whether the caller went away, which a synchronous stream is
// not told otherwise.
#include <cmath>

#include "database_status.h"
#include "reception_reader.h"
#include "request_validation.h"
#include "teleop_service.h"

namespace dtmf::server {

namespace {

constexpr std::uint32_t kDefaultReceptions = 100;
constexpr std::uint32_t kMaxReceptions = 10000;
constexpr auto kCancelCheck = std::chrono::milliseconds(250);

void fill_reception(v1::Reception& out, const store::ReceptionRecord& r, const std::vector<RobotStatus>& robots) {
  out.set_id(r.id);
  out.set_stored(r.stored);
  if (r.robot_address) {
    out.set_address(static_cast<std::uint32_t>(*r.robot_address));
    for (const RobotStatus& robot : robots)
      if (robot.address == *r.robot_address) out.set_robot(robot.name);
  }
  out.set_host(r.host);
  out.set_profile(r.profile);
  out.set_heard_unix_ms(std::llround(r.heard_unix_ms));
  out.set_intact(r.crc_ok);
  out.set_event(r.crc_ok ? r.event : "broken");
  out.set_reason(r.reason);
  out.set_authenticated(r.authenticated);
  out.set_reply(r.reply);
  out.set_command(r.command);
  if (r.linear_mps) out.set_linear_mps(*r.linear_mps);
  if (r.angular_radps) out.set_angular_radps(*r.angular_radps);
}

}  // namespace

grpc::Status TeleopService::ListReceptions(grpc::ServerContext* context, const v1::ListReceptionsRequest* request,
                                           grpc::ServerWriter<v1::ListReceptionsResponse>* writer) {
  store::ReceptionQuery query;
  const std::vector<RobotStatus> robots = transmitter_.robots();
  try {
    check_robot_name("robot", request->robot());
    check_text("run_id", request->run_id(), kIdLimit);
    if (request->limit() > kMaxReceptions)
      throw RequestError("limit " + std::to_string(request->limit()) + " is over the cap: give 0 (" +
                         std::to_string(kDefaultReceptions) + ") up to " + std::to_string(kMaxReceptions));
    if (!request->robot().empty()) query.robot_address = robots.at(transmitter_.robot_named(request->robot())).address;
  } catch (const RequestError& e) {
    return e.status();
  } catch (const std::invalid_argument& e) {
    return {grpc::StatusCode::NOT_FOUND, std::string("robot: ") + e.what()};
  }
  if (request->run_case() == v1::ListReceptionsRequest::kRunId) query.run = request->run_id();
  if (request->run_case() == v1::ListReceptionsRequest::kRunNumber) query.run = std::int64_t{request->run_number()};
  query.limit = static_cast<int>(request->limit() == 0 ? kDefaultReceptions : request->limit());
  if (store::database_disabled(options_.database)) return no_database();
  try {
    // Listening before the first read: nothing stored in between is missed.
    std::optional<store::ReceptionFeed> feed;
    if (request->follow()) feed.emplace(options_.database);
    const store::ReceptionReader reader(options_.database);
    for (bool announced = true; !context->IsCancelled();) {
      if (announced) {
        const auto records = reader.list(query);
        if (!records) return {grpc::StatusCode::NOT_FOUND, "no such test run (see ListRuns)"};
        for (const auto& r : *records) {
          v1::ListReceptionsResponse response;
          fill_reception(*response.mutable_reception(), r, robots);
          if (!writer->Write(response)) return grpc::Status::CANCELLED;
          query.after_stored = r.stored;
        }
        query.limit = static_cast<int>(kMaxReceptions);  // from now on, everything new
      }
      if (!feed) return grpc::Status::OK;
      announced = feed->wait(kCancelCheck);
    }
    return grpc::Status::CANCELLED;
  } catch (const std::exception& e) {
    return database_trouble(e);
  }
}

}  // namespace dtmf::server
