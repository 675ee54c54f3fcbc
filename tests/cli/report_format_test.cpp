// dtmfctl report's figures for waits for the air (migration 014): how many frames waited,
// all their waits, and the longest a command waited, in the table and in --json / --csv.
#include "report_format.h"

#include <gtest/gtest.h>

using namespace dtmf;

TEST(ReportFormat, WaitsForTheAirAreInTheTableAndTheJson) {
  v1::GetReportResponse r;
  r.mutable_run()->set_label("jammed");
  r.set_air_waits(4);
  r.set_air_wait_total_ms(9350);
  r.set_air_wait_max_ms(8700);
  const nlohmann::ordered_json json = cli::report_json(r);
  EXPECT_EQ(json["air_waits"], 4);
  EXPECT_EQ(json["air_wait_total_ms"], 9350);
  EXPECT_EQ(json["air_wait_max_ms"], 8700);
  ::testing::internal::CaptureStdout();
  cli::print_table(r);
  const std::string table = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(table.find("Frames that waited for the air"), std::string::npos) << table;
  EXPECT_NE(table.find("9350.00 ms"), std::string::npos) << table;
  EXPECT_NE(table.find("8700.00 ms"), std::string::npos) << table;

  r.clear_air_wait_max_ms();  // nothing waited: no longest wait
  EXPECT_TRUE(cli::report_json(r)["air_wait_max_ms"].is_null());
}
