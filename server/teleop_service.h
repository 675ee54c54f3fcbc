// The gRPC service dtmf.v1.TeleopService: validates requests, queues commands on the transmitter
// and streams their progress; keeps labelled test runs and reads their reports from the
// database. Who may call is settled before, in the transport (bearer_token_auth.h).
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "request_validation.h"
#include "store.h"
#include "transmitter.h"

#include "command/robot_model.h"

namespace dtmf::server {

struct ServiceOptions {
  store::DatabaseUrl database;  // for reports
  CommandSettings defaults{Policy::Fail, std::chrono::seconds(60)};
  std::string host;
};

class TeleopSession;

// A command's progress event as the API streams it.
void fill_progress(v1::Progress& out, Job& job, const ProgressEvent& event, const std::string& robot);

// WatchAir is a callback method (watch_air_rpc.h: a reactor, no thread of its own); the rest are synchronous.
class TeleopService final : public v1::TeleopService::WithCallbackMethod_WatchAir<v1::TeleopService::Service> {
 public:
  TeleopService(Transmitter& transmitter, store::Store& store, ServiceOptions options);

  grpc::Status Drive(grpc::ServerContext*, const v1::DriveRequest*, grpc::ServerWriter<v1::DriveResponse>*) override;
  grpc::Status Turn(grpc::ServerContext*, const v1::TurnRequest*, grpc::ServerWriter<v1::TurnResponse>*) override;
  grpc::Status Stop(grpc::ServerContext*, const v1::StopRequest*, grpc::ServerWriter<v1::StopResponse>*) override;
  grpc::Status Reset(grpc::ServerContext*, const v1::ResetRequest*, grpc::ServerWriter<v1::ResetResponse>*) override;
  grpc::Status RunTestSequence(grpc::ServerContext*, const v1::RunTestSequenceRequest*,
                               grpc::ServerWriter<v1::RunTestSequenceResponse>*) override;
  grpc::Status Teleop(grpc::ServerContext*,
                      grpc::ServerReaderWriter<v1::TeleopResponse, v1::TeleopRequest>* stream) override;
  grpc::Status Decide(grpc::ServerContext*, const v1::DecideRequest*, v1::DecideResponse*) override;
  grpc::Status StartRun(grpc::ServerContext*, const v1::StartRunRequest*, v1::StartRunResponse*) override;
  grpc::Status EndRun(grpc::ServerContext*, const v1::EndRunRequest*, v1::EndRunResponse*) override;
  grpc::Status ListRuns(grpc::ServerContext*, const v1::ListRunsRequest*, v1::ListRunsResponse*) override;
  grpc::Status GetReport(grpc::ServerContext*, const v1::GetReportRequest*, v1::GetReportResponse*) override;
  grpc::Status ListRobots(grpc::ServerContext*, const v1::ListRobotsRequest*, v1::ListRobotsResponse*) override;
  grpc::Status ListReceptions(grpc::ServerContext* context, const v1::ListReceptionsRequest* request,
                              grpc::ServerWriter<v1::ListReceptionsResponse>* writer) override;
  grpc::ServerWriteReactor<v1::WatchAirResponse>* WatchAir(grpc::CallbackServerContext*,
                                                           const v1::WatchAirRequest* request) override;

 private:
  // Queues `command` and writes its progress through `write` until it ends.
  template <class Write>
  grpc::Status run_command(grpc::ServerContext* context, const command::Command& command,
                           const v1::CommandOptions& options, bool to_front, Write write);
  // Writes the progress of `job` through `write` until it ends; its status.
  template <class Write>
  grpc::Status follow(grpc::ServerContext* context, const std::shared_ptr<Job>& job, const std::string& robot,
                      Write write);
  // Stop with all_robots: every Teleop stream halted, one stop every robot executes.
  grpc::Status stop_every_robot(grpc::ServerContext* context, const v1::StopRequest& request,
                                grpc::ServerWriter<v1::StopResponse>* writer);
  // The request's options over the server's defaults, with the profile the command goes out
  // under (Transmitter::sendable_profile: with a key, a Stop always authenticated); throws
  // RequestError.
  CommandSettings settings_of(const v1::CommandOptions& options, bool stop = false) const;
  grpc::Status start_run(const std::string& label, const std::string& notes, const LinkProfile& profile,
                         std::string& run_id);
  grpc::Status end_run(const std::string& run_id);
  // The request's target for the robot model; throws RequestError naming the field.
  command::Velocity teleop_target(const v1::TeleopRequest& request, RobotIndex robot) const;
  // FAILED_PRECONDITION naming `rpc` while a Teleop stream drives the robot `options` name
  // (nothing for a name no robot has: the command's own checks refuse it).
  std::optional<grpc::Status> refuse_while_teleop(const char* rpc, const v1::CommandOptions& options);
  // Stop overtook: the driving stream sends nothing more and ends.
  void halt_teleop(const v1::CommandOptions& options);
  void halt_every_teleop();

  Transmitter& transmitter_;
  store::Store& store_;
  ServiceOptions options_;
  std::mutex runs_mutex_;
  std::optional<store::TestRunRow> active_run_;
  std::mutex teleop_mutex_;
  // Each robot's slot (teleop_stream.h: TeleopSlot): one stream drives a robot at a time,
  // and streams to different robots share the transmitter's queue.
  std::vector<std::weak_ptr<TeleopSession>> teleop_;
};

}  // namespace dtmf::server
