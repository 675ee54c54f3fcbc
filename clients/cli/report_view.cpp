#include "report_view.h"

#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "grpc/health/v1/health.grpc.pb.h"

namespace dtmf::cli {

namespace {

struct ReportOptions {
  ServerOptions server;
  std::string run;  // number or uuid; empty: the latest
  bool json = false;
  bool csv = false;
  unsigned limit = 20;
};

std::string percent(bool has, double value) {
  if (!has) return "N/A";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f%%", value);
  return text;
}

std::string ms(bool has, double value) {
  if (!has) return "N/A";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f ms", value);
  return text;
}

std::string when(std::int64_t unix_ms) {
  if (unix_ms == 0) return "-";
  const std::time_t t = static_cast<std::time_t>(unix_ms / 1000);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
  return text;
}

// The report's figures in the seed's order, as (name, value) pairs for JSON and CSV.
nlohmann::ordered_json report_json(const v1::GetReportResponse& r) {
  const auto optional = [](bool has, double v) { return has ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"run_number", r.run().number()},
          {"run_id", r.run().run_id()},
          {"label", r.run().label()},
          {"profile", r.run().profile()},
          {"transmissions_sent", r.transmissions_sent()},
          {"transmissions_received", r.transmissions_received()},
          {"successfully_matched", r.successfully_matched()},
          {"dropped", r.dropped()},
          {"false_positives", r.false_positives()},
          {"false_positive_rate_pct", optional(r.has_false_positive_rate_pct(), r.false_positive_rate_pct())},
          {"duplicates", r.duplicates()},
          {"successful_transmissions", r.successful_transmissions()},
          {"success_rate_pct", optional(r.has_success_rate_pct(), r.success_rate_pct())},
          {"sender_confirmed", r.sender_confirmed()},
          {"sender_confirmed_rate_pct", optional(r.has_sender_confirmed_rate_pct(), r.sender_confirmed_rate_pct())},
          {"crc_accepted", r.crc_accepted()},
          {"crc_rejected", r.crc_rejected()},
          {"negative_confirmations_sent", r.negative_confirmations_sent()},
          {"error_catch_rate_pct", optional(r.has_error_catch_rate_pct(), r.error_catch_rate_pct())},
          {"frame_attempts", r.frame_attempts()},
          {"response_time_avg_ms", optional(r.has_response_time_avg_ms(), r.response_time_avg_ms())},
          {"response_time_min_ms", optional(r.has_response_time_min_ms(), r.response_time_min_ms())},
          {"response_time_max_ms", optional(r.has_response_time_max_ms(), r.response_time_max_ms())},
          {"latency_avg_ms", optional(r.has_latency_avg_ms(), r.latency_avg_ms())},
          {"latency_min_ms", optional(r.has_latency_min_ms(), r.latency_min_ms())},
          {"latency_max_ms", optional(r.has_latency_max_ms(), r.latency_max_ms())},
          {"refused", r.refused()},
          {"refused_authentication", r.refused_authentication()},
          {"sender_confirmed_unauthenticated", r.sender_confirmed_unauthenticated()},
          {"refused_authentication_peak_per_minute", r.refused_authentication_peak_per_minute()}};
}

// The layout of the seed's Appendix A: counts and rates side by side, then the times.
void print_table(const v1::GetReportResponse& r) {
  std::printf("Test Results - %s   (run %lld, profile %s, %s)\n", r.run().label().c_str(),
              static_cast<long long>(r.run().number()), r.run().profile().c_str(),
              when(r.run().started_unix_ms()).c_str());
  const auto row = [](const char* a, const std::string& av, const char* b, const std::string& bv) {
    std::printf("  %-30s %10s    %-28s %10s\n", a, av.c_str(), b, bv.c_str());
  };
  const auto n = [](std::int64_t v) { return std::to_string(v); };
  row("Total transmission sent", n(r.transmissions_sent()), "Successful transmissions",
      n(r.successful_transmissions()));
  row("Total transmission received", n(r.transmissions_received()), "Success rate",
      percent(r.has_success_rate_pct(), r.success_rate_pct()));
  row("Successfully matched", n(r.successfully_matched()), "Sender confirmed rate",
      percent(r.has_sender_confirmed_rate_pct(), r.sender_confirmed_rate_pct()));
  row("Dropped", n(r.dropped()), "CRC accepted", n(r.crc_accepted()));
  row("False positive", n(r.false_positives()), "CRC rejected", n(r.crc_rejected()));
  row("False positive rate", percent(r.has_false_positive_rate_pct(), r.false_positive_rate_pct()),
      "Negative confirmation sent", n(r.negative_confirmations_sent()));
  row("Duplicates", n(r.duplicates()), "Error catch rate",
      percent(r.has_error_catch_rate_pct(), r.error_catch_rate_pct()));
  row("Refused", n(r.refused()), "Refused for authentication", n(r.refused_authentication()));
  row("Confirmed without a tag", n(r.sender_confirmed_unauthenticated()), "Most refused in a minute",
      n(r.refused_authentication_peak_per_minute()));
  std::printf("\n");
  row("Average response time", ms(r.has_response_time_avg_ms(), r.response_time_avg_ms()), "Average latency",
      ms(r.has_latency_avg_ms(), r.latency_avg_ms()));
  row("Min response time", ms(r.has_response_time_min_ms(), r.response_time_min_ms()), "Min latency",
      ms(r.has_latency_min_ms(), r.latency_min_ms()));
  row("Max response time", ms(r.has_response_time_max_ms(), r.response_time_max_ms()), "Max latency",
      ms(r.has_latency_max_ms(), r.latency_max_ms()));
}

void print_csv(const v1::GetReportResponse& r) {
  const nlohmann::ordered_json fields = report_json(r);
  std::string header, values;
  for (const auto& [name, value] : fields.items()) {
    header += (header.empty() ? "" : ",") + name;
    values += (values.empty() ? "" : ",") + (value.is_null()     ? std::string()
                                             : value.is_string() ? value.get<std::string>()
                                                                 : value.dump());
  }
  std::printf("%s\n%s\n", header.c_str(), values.c_str());
}

grpc::Status fetch_report(ServerConnection& connection, const std::string& run, v1::GetReportResponse& report) {
  v1::GetReportRequest request;
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
  const grpc::Status status = fetch_report(connection, o.run, report);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
    if (caller_refused(status)) return kExitNotAuthorized;
    return status.error_code() == grpc::StatusCode::UNAVAILABLE ? kExitUnreachable : kExitUnconfirmed;
  }
  if (o.json)
    std::printf("%s\n", report_json(report).dump().c_str());
  else if (o.csv)
    print_csv(report);
  else
    print_table(report);
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
                                         {"transmissions_sent", run.transmissions_sent()}}
                              .dump()
                              .c_str());
    } else {
      std::printf("%4lld  %-12s %-6s %s  %3lld frames  %s\n", static_cast<long long>(run.number()), run.label().c_str(),
                  run.profile().c_str(), when(run.started_unix_ms()).c_str(),
                  static_cast<long long>(run.transmissions_sent()), run.ended_unix_ms() ? "" : "(running)");
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
      return body(*o);
    };
  };
  CLI::App* runs = app.add_subcommand("runs", "list the test runs, newest first");
  runs->add_option("--limit", o->limit, "how many, 0 for all")->capture_default_str();
  runs->callback([with_global, &run] { run = with_global(run_runs); });

  CLI::App* report = app.add_subcommand("report", "a run's report in the layout of the seed's Appendix A tables");
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
