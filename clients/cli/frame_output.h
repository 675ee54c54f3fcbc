// How dtmfctl prints a frame: a readable line on a terminal, one JSON object per line with
// --json (fields: word, frame, crc, tones_hz, and t_ms / crc_ok / event when decoding).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "link/receiver_path.h"
#include "link/sender_path.h"

namespace dtmf::cli {

nlohmann::json frame_json(const link::PlannedFrame& frame);
std::string frame_line(const link::PlannedFrame& frame);

// What an intact frame did to the robot's command state, e.g. "reset -> mode_select".
std::string event_text(const command::ReceiverEvent& event);
nlohmann::json event_json(const command::ReceiverEvent& event);

}  // namespace dtmf::cli
