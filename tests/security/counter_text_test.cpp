// The counter files' text (security/counter_text.h): read back only as written, and every
// other text named for what is wrong with it.
#include <gtest/gtest.h>

#include "security/counter_text.h"
#include "security/freshness.h"

using namespace dtmf::security;

namespace {

// What take_line says is wrong with `text` as line 1 "reserved N", or "" when it reads.
std::string damage(std::string_view text) {
  try {
    counter_text::take_line(text, "reserved", 1);
    return "";
  } catch (const counter_text::Damage& d) {
    return d.what;
  }
}

}  // namespace

TEST(CounterText, ReadsTheLinesAsWrittenAndNothingAfterThem) {
  std::string_view text = "reserved 120\nconfirmed 0\n";
  EXPECT_EQ(counter_text::take_line(text, "reserved", 1), 120u);
  EXPECT_EQ(counter_text::take_line(text, "confirmed", 2), 0u);
  EXPECT_NO_THROW(counter_text::expect_end(text));
  EXPECT_THROW(counter_text::expect_end("x"), counter_text::Damage);
  std::string_view short_text = "reserved 1\n";
  counter_text::take_line(short_text, "reserved", 1);
  EXPECT_THROW(counter_text::take_line(short_text, "confirmed", 2), counter_text::Damage);
}

TEST(CounterText, EveryOtherFormIsNamedForWhatIsWrong) {
  EXPECT_EQ(damage(""), "it is empty");
  EXPECT_NE(damage("reserved 12").find("cut short"), std::string::npos);
  EXPECT_NE(damage("reserve 12\n").find("where 'reserved <number>' belongs"), std::string::npos);
  EXPECT_NE(damage("reserved 012\n").find("not a decimal number"), std::string::npos);
  EXPECT_NE(damage("reserved -1\n").find("not a decimal number"), std::string::npos);
  EXPECT_NE(damage("reserved  1\n").find("not a decimal number"), std::string::npos);
  EXPECT_NE(damage("reserved " + std::to_string(kCounterLimit) + "\n").find("beyond the"), std::string::npos);
  EXPECT_EQ(damage("reserved " + std::to_string(kCounterLimit - 1) + "\n"), "");
  // Unprintable bytes are shown escaped, and a long line cut.
  EXPECT_EQ(counter_text::shown(std::string("a\x01'") + std::string(50, 'b')),
            "a\\x01\\x27" + std::string(37, 'b') + "...");
}
