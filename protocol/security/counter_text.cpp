#include "security/counter_text.h"

#include <algorithm>
#include <cstdio>

#include "security/freshness.h"

namespace dtmf::security::counter_text {

std::string shown(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f && c != '\'' && c != '\\') {
      out += c;
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", u);
      out += escaped;
    }
  }
  return text.size() > 40 ? out + "..." : out;
}

std::uint64_t take_line(std::string_view& text, std::string_view name, int number) {
  const std::string line_name = "line " + std::to_string(number);
  if (text.empty()) throw Damage{number == 1 ? "it is empty" : line_name + " is missing"};
  const std::size_t end = text.find('\n');
  if (end == std::string_view::npos) {
    throw Damage{line_name + ", '" + shown(text) + "', is cut short (it has no end of line)"};
  }
  const std::string_view line = text.substr(0, end);
  const std::string expected = std::string(name) + " <number>";
  if (line.size() <= name.size() || line.substr(0, name.size()) != name || line[name.size()] != ' ') {
    throw Damage{line_name + " is '" + shown(line) + "', where '" + expected + "' belongs"};
  }
  const std::string_view digits = line.substr(name.size() + 1);
  const bool decimal = !digits.empty() &&
                       std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
                       (digits.size() == 1 || digits[0] != '0');
  if (!decimal) {
    throw Damage{line_name + " is '" + shown(line) + "': its value is not a decimal number, where '" + expected +
                 "' belongs"};
  }
  std::uint64_t value = 0;
  for (const char c : digits) {
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
    if (value >= kCounterLimit) {
      throw Damage{line_name + " is '" + shown(line) + "': its value is beyond the " + std::to_string(kCounterBits) +
                   "-bit counter"};
    }
  }
  text.remove_prefix(end + 1);
  return value;
}

void expect_end(std::string_view text) {
  if (!text.empty()) throw Damage{"it goes on after its last line: '" + shown(text) + "'"};
}

}  // namespace dtmf::security::counter_text
