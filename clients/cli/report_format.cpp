// dtmfctl report's output: the seed's Appendix A table, JSON and CSV of a run's report (for
// the whole room, or one robot of it).
#include "report_format.h"

#include <cstdio>
#include <ctime>

namespace dtmf::cli {

namespace {

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

}  // namespace

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
  nlohmann::ordered_json fields = {
      {"run_number", r.run().number()},
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
  // A room of robots (migration 010): the robot reported, null for the whole room.
  fields["robot"] = r.robot().empty() ? nlohmann::json(nullptr) : nlohmann::json(r.robot());
  fields["every_robot_stops_sent"] = r.every_robot_stops_sent();
  fields["every_robot_stops_executed"] = r.every_robot_stops_executed();
  fields["renewals_sent"] = r.renewals_sent();
  fields["renewals_executed"] = r.renewals_executed();
  // Waits for the air (listen before talk).
  fields["air_waits"] = r.air_waits();
  fields["air_wait_total_ms"] = r.air_wait_total_ms();
  fields["air_wait_max_ms"] = optional(r.has_air_wait_max_ms(), r.air_wait_max_ms());
  return fields;
}

// The layout of the seed's Appendix A: counts and rates side by side, then the times.
void print_table(const v1::GetReportResponse& r) {
  std::printf(
      "Test Results - %s   (run %lld, profile %s, %s%s)\n", r.run().label().c_str(),
      static_cast<long long>(r.run().number()), r.run().profile().c_str(), when(r.run().started_unix_ms()).c_str(),
      r.robot().empty() ? (r.run().robots_size() > 1 ? ", the whole room" : "") : (", robot " + r.robot()).c_str());
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
  if (r.every_robot_stops_sent() > 0)
    row("Stops for every robot sent", n(r.every_robot_stops_sent()), "Executed by robots",
        n(r.every_robot_stops_executed()));
  if (r.renewals_sent() > 0)
    row("Joint renewals sent", n(r.renewals_sent()), "Taken by robots", n(r.renewals_executed()));
  row("Frames that waited for the air", n(r.air_waits()), "Waited for the air in all", ms(true, r.air_wait_total_ms()));
  std::printf("\n");
  row("Average response time", ms(r.has_response_time_avg_ms(), r.response_time_avg_ms()), "Average latency",
      ms(r.has_latency_avg_ms(), r.latency_avg_ms()));
  row("Min response time", ms(r.has_response_time_min_ms(), r.response_time_min_ms()), "Min latency",
      ms(r.has_latency_min_ms(), r.latency_min_ms()));
  row("Max response time", ms(r.has_response_time_max_ms(), r.response_time_max_ms()), "Max latency",
      ms(r.has_latency_max_ms(), r.latency_max_ms()));
  // A command's waits for the air, its frames together: at most 8.7 s (docs/protocol.md §9).
  row("Longest a command waited (air)", ms(r.has_air_wait_max_ms(), r.air_wait_max_ms()), "", "");
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

}  // namespace dtmf::cli
