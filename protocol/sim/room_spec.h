// Physical layer, rooms: rooms written as text, for programs and scripts.
//
//   size        "7x9x3" (metres along x, y, z; z up)
//   position    "1.5,2,0.05" (metres from the x = 0, y = 0 walls and the floor)
//   reflection  "[SURFACES=]VALUES": SURFACES one or more of walls (the four side walls),
//               ceiling, floor, x0, x1, y0, y1, all, joined by '+'; without them the four
//               walls and the ceiling (the floor keeps its own: a robot's floor is hard).
//               VALUES a coefficient for every band, "0.9", or per band "125:0.7,1000:0.9"
//               (Hz:coefficient, interpolated on a log-frequency axis, constant beyond).
//   range       "0.5:20" (metres, min:max)
// Each parser throws std::invalid_argument saying what is wrong and giving an example;
// the messages name no program's flags (that is the caller's part).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/image_source_room.h"

namespace dtmf::sim {

Point3 parse_room_size(const std::string& text);
Point3 parse_position(const std::string& text);
std::pair<double, double> parse_range(const std::string& text);

// Sets the surfaces the text names; returns them.
std::vector<Surface> apply_reflection(ShoeboxRoom& room, const std::string& text);

}  // namespace dtmf::sim
