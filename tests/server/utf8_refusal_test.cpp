// Pins what server/utf8_refusal.cpp relies on: that this protobuf, refusing a string that
// is not UTF-8, names the field (it does so in a log line until protobuf 22 moved logging
// to Abseil). If an upgrade loses that, refusals still come as INVALID_ARGUMENT but name no
// field, and this test says so instead of the API quietly getting worse.
#include "utf8_refusal.h"

#include <google/protobuf/stubs/common.h>
#include <gtest/gtest.h>

TEST(Utf8Refusal, ThisProtobufNamesTheStringFieldItRefuses) {
  EXPECT_TRUE(dtmf::server::utf8_refusal_names_fields())
      << "protobuf " << GOOGLE_PROTOBUF_VERSION
      << " no longer names the field of a string that is not UTF-8 where server/utf8_refusal.cpp listens "
         "(SetLogHandler). Find where it reports the field now (for protobuf >= 22, an absl::LogSink) and "
         "hook that, or validate UTF-8 in a custom request deserializer.";
}
