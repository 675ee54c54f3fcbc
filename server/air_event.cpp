#include "air_event.h"

#include <algorithm>

#include "command/overloaded.h"

namespace dtmf::server {

bool concerns(const AirEvent& event, const std::string& robot) {
  if (robot.empty()) return true;
  const auto named = [&robot](const std::string& r) { return r.empty() || r == robot; };
  return std::visit(command::Overloaded{
                        [&](const FramePlayed& e) {
                          return e.robots.empty() ||
                                 std::find(e.robots.begin(), e.robots.end(), robot) != e.robots.end();
                        },
                        [&](const FrameAnswered& e) { return e.robot == robot; },
                        [&](const AnswerHeard& e) { return named(e.robot); },
                        [&](const AirWaiting& e) { return named(e.robot); },
                        [](const AirBusy&) { return true; },
                        [&](const CommandEnded& e) { return named(e.robot); },
                        [](const SpectrumColumn&) { return true; },
                    },
                    event.what);
}

}  // namespace dtmf::server
