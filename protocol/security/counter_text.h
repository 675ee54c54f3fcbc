// Security layer: the text of a counter file ("reserved N" / "confirmed N" lines), read back
// only exactly as it is written, and for text that is not, what is wrong with it, in words a
// person can act on (security/counter_file.h says where the files live and when they are
// written). Pure logic.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace dtmf::security::counter_text {

// A counter file that is not in the form written here: what is wrong with it.
struct Damage {
  std::string what;
};

// `text` for a message: at most 40 characters, anything unprintable as \xNN.
std::string shown(std::string_view text);

// Takes the line "NAME N\n" off the front of `text` and gives N, exactly as written here: N in
// decimal, with no sign, no leading zero and no space around it, below the counter's limit.
// Throws Damage naming line `number` (from 1) and what is wrong with it.
std::uint64_t take_line(std::string_view& text, std::string_view name, int number);

// Throws Damage when anything follows the last line.
void expect_end(std::string_view text);

}  // namespace dtmf::security::counter_text
