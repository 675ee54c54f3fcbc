#include "report_view.h"

#include "report_format.h"

#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "grpc/health/v1/health.grpc.pb.h"

namespace dtmf::cli {

namespace {

struct ReportOptions {
  ServerOptions server;
  std::string run;    // number or uuid; empty: the latest
  std::string robot;  // one robot of the run (dtmfctl --robot); empty: the whole room
  bool json = false;
  bool csv = false;
  unsigned limit = 20;
};

grpc::Status fetch_report(ServerConnection& connection, const std::string& run, v1::GetReportResponse& report,
                          const std::string& robot = "") {
  v1::GetReportRequest request;
  request.set_robot(robot);
  if (!run.empty()) {
    if (run.find_first_not_of("0123456789") == std::string::npos)
      request.set_run_number(std::stoll(run));
    else
      request.set_run_id(run);
  }
  auto context = connection.context();
  return connection.teleop().GetReport(context.get(), request, &report);
}

int run_report(const ReportOptions& o) {
  ServerConnection connection(o.server);
  v1::GetReportResponse report;
  const grpc::Status status = fetch_report(connection, o.run, report, o.robot);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
    if (caller_refused(status)) return kExitNotAuthorized;
    return status.error_code() == grpc::StatusCode::UNAVAILABLE ? kExitUnreachable : kExitUnconfirmed;
  }
  if (o.json) {
    std::printf("%s\n", report_json(report).dump().c_str());
  } else if (o.csv) {
    print_csv(report);
  } else {
    print_table(report);
    // The whole room of several robots: then each robot's table (--robot NAME: one).
    if (o.robot.empty() && report.run().robots_size() > 1) {
      for (const std::string& robot : report.run().robots()) {
        v1::GetReportResponse own;
        if (!fetch_report(connection, report.run().run_id(), own, robot).ok()) continue;
        std::printf("\n");
        print_table(own);
      }
    }
  }
  return 0;
}

int run_runs(const ReportOptions& o) {
  ServerConnection connection(o.server);
  v1::ListRunsRequest request;
  request.set_limit(o.limit);
  v1::ListRunsResponse runs;
  auto context = connection.context();
  const grpc::Status status = connection.teleop().ListRuns(context.get(), request, &runs);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
    return caller_refused(status) ? kExitNotAuthorized : kExitUnconfirmed;
  }
  for (const auto& run : runs.runs()) {
    if (o.json) {
      std::printf("%s\n", nlohmann::json{{"number", run.number()},
                                         {"run_id", run.run_id()},
                                         {"label", run.label()},
                                         {"profile", run.profile()},
                                         {"started_unix_ms", run.started_unix_ms()},
                                         {"ended_unix_ms", run.ended_unix_ms()},
                                         {"transmissions_sent", run.transmissions_sent()},
                                         {"robots", std::vector<std::string>(run.robots().begin(), run.robots().end())}}
                              .dump()
                              .c_str());
    } else {
      std::string robots;
      for (const auto& r : run.robots()) robots += (robots.empty() ? "robots " : ", ") + r;
      std::printf("%4lld  %-12s %-6s %s  %3lld frames  %s%s\n", static_cast<long long>(run.number()),
                  run.label().c_str(), run.profile().c_str(), when(run.started_unix_ms()).c_str(),
                  static_cast<long long>(run.transmissions_sent()), robots.c_str(),
                  run.ended_unix_ms() ? "" : " (running)");
    }
  }
  return 0;
}

int run_robots(const ReportOptions& o) {
  ServerConnection connection(o.server);
  v1::ListRobotsResponse robots;
  auto context = connection.context();
  const grpc::Status status = connection.teleop().ListRobots(context.get(), {}, &robots);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
    return caller_refused(status) ? kExitNotAuthorized : kExitUnreachable;
  }
  for (const auto& r : robots.robots()) {
    if (o.json) {
      std::printf("%s\n", nlohmann::json{{"name", r.name()},
                                         {"address", r.address()},
                                         {"key_id", r.key_id()},
                                         {"model", r.model()},
                                         {"last_answered_unix_ms", r.last_answered_unix_ms()}}
                              .dump()
                              .c_str());
    } else {
      std::printf("%-16s address %u  %-8s key %-18s last answered %s\n", r.name().c_str(), r.address(),
                  r.model().c_str(), r.key_id().empty() ? "none" : r.key_id().c_str(),
                  r.last_answered_unix_ms() ? when(r.last_answered_unix_ms()).c_str() : "never");
    }
  }
  return 0;
}

int run_health(const ReportOptions& o) {
  ServerConnection connection(o.server);
  auto health = grpc::health::v1::Health::NewStub(connection.channel());
  auto context = connection.context();
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = health->Check(context.get(), {}, &response);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
    return kExitUnreachable;
  }
  const bool serving = response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
  std::printf("%s: %s\n", o.server.address.c_str(), serving ? "SERVING" : "NOT_SERVING");
  return serving ? 0 : kExitUnreachable;
}

}  // namespace

void print_report_of(ServerConnection& connection, const std::string& run_id) {
  v1::GetReportResponse report;
  const grpc::Status status = fetch_report(connection, run_id, report);
  if (status.ok())
    print_table(report);
  else
    std::printf("(no report: %s)\n", describe_status(status).c_str());
}

void add_run_commands(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<ReportOptions>();
  // The connection and --json are global options, read when the subcommand runs.
  const auto with_global = [o, &global](int (*body)(const ReportOptions&)) {
    return [o, &global, body] {
      o->server = global.server;
      o->json = global.json;
      o->robot = global.robot;
      return body(*o);
    };
  };
  CLI::App* runs = app.add_subcommand("runs", "list the test runs, newest first");
  runs->add_option("--limit", o->limit, "how many, 0 for all")->capture_default_str();
  runs->callback([with_global, &run] { run = with_global(run_runs); });

  CLI::App* report = app.add_subcommand(
      "report",
      "a run's report in the layout of the seed's Appendix A tables: the whole room, then each robot (--robot: one)");
  report->add_option("run", o->run, "run number or id (default: the latest run)");
  report->add_flag("--csv", o->csv, "as CSV: a header line and a value line (--json: as one JSON object)");
  report->callback([o, with_global, &global, &run] {
    if (o->csv && global.json) throw CLI::ValidationError("report", "--csv and --json exclude each other: choose one");
    run = with_global(run_report);
  });

  CLI::App* robots = app.add_subcommand("robots", "the robots the server drives: names, addresses, keys, models");
  robots->callback([with_global, &run] { run = with_global(run_robots); });

  CLI::App* health = app.add_subcommand("health", "is the server up and serving?");
  health->callback([with_global, &run] { run = with_global(run_health); });
}

}  // namespace dtmf::cli
