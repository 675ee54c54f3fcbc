// How text someone else wrote goes into an error or a log line: a robot's name or a field of
// the robots file, a request's string. Such text reaches terminals and journals, so it is
// shown quoted, on one line, and short: a raw newline would forge a log line, an escape
// sequence would rewrite the operator's terminal, and a 3 MB name would bury everything else.
// Every place the server echoes such text goes through shown(). (security/counter_text.h has
// its own for a counter file's bytes, cut at 40: protocol/ cannot include the server.)
// Header-only, pure logic.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace dtmf::server {

inline constexpr std::size_t kShownBytes = 64;

// `text` in double quotes, each byte outside printable ASCII escaped (\n, \r, \t, \", \\,
// else \xNN: a terminal sees no control character, a UTF-8 byte or a bidirectional mark),
// at most its first 64 bytes; a longer text is followed by `... (N bytes, first 64 shown)`.
inline std::string shown(std::string_view text) {
  std::string out = "\"";
  for (const char c : text.substr(0, kShownBytes)) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    }
  }
  out += '"';
  if (text.size() > kShownBytes) {
    out += "... (" + std::to_string(text.size()) + " bytes, first " + std::to_string(kShownBytes) + " shown)";
  }
  return out;
}

}  // namespace dtmf::server
