// How dtmfctl watch shows the air (WatchAir): one line per event, its time on the microphone's
// clock first; with --json, each message as one JSON object (the proto's field names). What a
// watcher lost for reading too slowly is said on a line of its own, before the entry after it.
// dtmfctl heard shows what robots heard and did (ListReceptions) the same way.
#pragma once

#include <string>

#include "dtmf/v1/teleop.pb.h"

namespace dtmf::cli {

// The line (or lines) for `message`, each ending in a newline.
std::string watch_lines(const v1::WatchAirResponse& message);
std::string watch_json(const v1::WatchAirResponse& message);
// dtmfctl heard: one line per reception (ListReceptions), its wall time first.
std::string reception_line(const v1::Reception& reception);
// Any message as one JSON line, the proto's field names.
std::string json_line(const google::protobuf::Message& message);

}  // namespace dtmf::cli
