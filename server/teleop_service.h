// The gRPC service dtmf.v1.TeleopService: validates requests, queues commands on the transmitter
// and streams their progress; keeps labelled test runs and reads their reports from the
// database. Who may call is settled before, in the transport (bearer_token_auth.h).
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "request_validation.h"
#include "store.h"
#include "teleop_stream.h"
#include "transmitter.h"

#include "command/robot_model.h"

namespace dtmf::server {

struct ServiceOptions {
  store::DatabaseUrl database;  // for reports
  CommandSettings defaults{Policy::Fail, std::chrono::seconds(60)};
  std::string host;
};

// A command's progress event as the API streams it.
void fill_progress(v1::Progress& out, Job& job, const ProgressEvent& event, const std::string& robot);

// The streams that follow the air are callback methods, each a small reactor with no thread
// of its own: the commands (command_reactor.h), Teleop (teleop_stream.h) and WatchAir
// (watch_air_rpc.h). The rest, which read the database or answer at once, are synchronous.
using TeleopServiceBase = v1::TeleopService::WithCallbackMethod_Drive<v1::TeleopService::WithCallbackMethod_Turn<
    v1::TeleopService::WithCallbackMethod_Stop<v1::TeleopService::WithCallbackMethod_Reset<
        v1::TeleopService::WithCallbackMethod_RunTestSequence<v1::TeleopService::WithCallbackMethod_Teleop<
            v1::TeleopService::WithCallbackMethod_WatchAir<v1::TeleopService::Service>>>>>>>;

class TeleopService final : public TeleopServiceBase {
 public:
  TeleopService(Transmitter& transmitter, store::Store& store, ServiceOptions options);

  grpc::ServerWriteReactor<v1::DriveResponse>* Drive(grpc::CallbackServerContext*, const v1::DriveRequest*) override;
  grpc::ServerWriteReactor<v1::TurnResponse>* Turn(grpc::CallbackServerContext*, const v1::TurnRequest*) override;
  grpc::ServerWriteReactor<v1::StopResponse>* Stop(grpc::CallbackServerContext*, const v1::StopRequest*) override;
  grpc::ServerWriteReactor<v1::ResetResponse>* Reset(grpc::CallbackServerContext*, const v1::ResetRequest*) override;
  grpc::ServerWriteReactor<v1::RunTestSequenceResponse>* RunTestSequence(grpc::CallbackServerContext*,
                                                                         const v1::RunTestSequenceRequest*) override;
  grpc::ServerBidiReactor<v1::TeleopRequest, v1::TeleopResponse>* Teleop(grpc::CallbackServerContext*) override;
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
  // Queues `command`; its job, or the status that refuses it.
  std::variant<std::shared_ptr<Job>, grpc::Status> submit(const command::Command& command,
                                                          const v1::CommandOptions& options, bool to_front);
  // Queues `command` and streams its progress until it ends (command_reactor.h).
  template <class Response>
  grpc::ServerWriteReactor<Response>* run_command(const command::Command& command, const v1::CommandOptions& options,
                                                  bool to_front);
  // Stop with all_robots: every Teleop stream halted, one stop every robot executes.
  grpc::ServerWriteReactor<v1::StopResponse>* stop_every_robot(const v1::StopRequest& request);
  // Teleop's first message: checked, and the robot's slot taken for `driver` (who calls,
  // named to any other caller refused meanwhile) (teleop_rpc.cpp).
  std::variant<TeleopOpened, grpc::Status> open_teleop(const v1::TeleopRequest& first, const std::string& driver);
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
  // ": held by ..." naming the client whose stream drives `robot`, or nothing.
  std::string held_by(RobotIndex robot);
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
