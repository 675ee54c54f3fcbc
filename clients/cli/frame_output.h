// How dtmfctl prints a frame, whatever its profile: a readable line on a terminal, or one
// JSON object per line with --json. Frames as planned: index, frame, crc, tones_hz, and
// word / sequence where the format has them. Frames as heard: t_ms, heard_ms, frame,
// crc_ok, and what the frame did (event; what).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "link/link.h"

namespace dtmf::cli {

nlohmann::json frame_json(const link::TransmitFrame& frame);
std::string frame_line(const link::TransmitFrame& frame);

nlohmann::json reception_json(const link::Reception& reception);
std::string reception_line(const link::Reception& reception);

}  // namespace dtmf::cli
