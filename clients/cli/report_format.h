// dtmfctl report's output: a run's report (GetReport) as the seed's Appendix A table, as one
// JSON object, or as CSV; and times as people read them.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "dtmf/v1/teleop.pb.h"

namespace dtmf::cli {

// "2026-11-22 15:30:00" in local time; "-" for 0.
std::string when(std::int64_t unix_ms);
// The report's figures in the seed's order, as (name, value) pairs for JSON and CSV.
nlohmann::ordered_json report_json(const v1::GetReportResponse& r);
// The layout of the seed's Appendix A: counts and rates side by side, then the times.
void print_table(const v1::GetReportResponse& r);
// A header line and a value line.
void print_csv(const v1::GetReportResponse& r);

}  // namespace dtmf::cli
