// How dtmfctl watch shows the air (WatchAir): one line per event, its time on the microphone's
// clock first; with --json, each message as one JSON object (the proto's field names). What a
// watcher lost for reading too slowly is said on a line of its own, before the entry after it.
#pragma once

#include <string>

#include "dtmf/v1/teleop.pb.h"

namespace dtmf::cli {

// The line (or lines) for `message`, each ending in a newline.
std::string watch_lines(const v1::WatchAirResponse& message);
std::string watch_json(const v1::WatchAirResponse& message);

}  // namespace dtmf::cli
