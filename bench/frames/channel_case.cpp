#include "frames/channel_case.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace dtmf::bench {

ChannelCase parse_channel_case(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw std::invalid_argument("--case '" + text +
                                "': write NAME=FLAGS, e.g. 'seminar=--rir bench/rirs/seminar_room_clap.wav'");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

sim::ChannelSetup channel_setup_of(const ChannelCase& c) {
  CLI::App app("case");
  sim::ChannelFlags flags;
  sim::add_channel_flags(app, flags);
  std::vector<std::string> words;
  std::istringstream in(c.flags);
  for (std::string w; in >> w;) words.push_back(w);
  std::reverse(words.begin(), words.end());  // CLI11 takes the arguments in reverse
  try {
    app.parse(words);
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument("case '" + c.name + "': " + e.what());
  }
  return sim::channel_setup(flags);
}

}  // namespace dtmf::bench
