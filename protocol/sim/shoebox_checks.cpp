// The shoebox room's checks and measures (image_source_room.h): what a room and a position in
// it must be, each refusal naming what is wrong and what to give instead, and the distance
// between two points.
#include <cmath>
#include <stdexcept>

#include "sim/image_source_room.h"
#include "sim/number_text.h"

namespace dtmf::sim {

std::string surface_name(Surface s) {
  static const char* names[] = {"wall x=0", "wall x=max", "wall y=0", "wall y=max", "floor", "ceiling"};
  return names[s];
}

void check_room(const ShoeboxRoom& room) {
  for (double side : {room.size_m.x, room.size_m.y, room.size_m.z}) {
    if (!std::isfinite(side) || side < kMinRoomSideM || side > kMaxRoomSideM) {
      throw std::invalid_argument("room side " + number_text(side) +
                                  " m: give sides between 0.5 and 200 m, e.g. 7x9x3");
    }
  }
  for (std::size_t s = 0; s < kSurfaces; ++s) {
    for (std::size_t b = 0; b < kOctaveBands; ++b) {
      const double r = room.reflection[s][b];
      if (!std::isfinite(r) || r < 0 || r >= 1) {
        throw std::invalid_argument("reflection coefficient " + number_text(r) + " of the " +
                                    surface_name(static_cast<Surface>(s)) + " at " + band_name(b) +
                                    ": give a value in [0, 1) (0.9 a furnished wall, 0.97 a hard floor)");
      }
    }
  }
  if (!std::isfinite(room.max_length_s) || room.max_length_s < 0.05 || room.max_length_s > 10) {
    throw std::invalid_argument("room response length cap " + number_text(room.max_length_s) + " s: give 0.05 to 10 s");
  }
  if (!std::isfinite(room.randomization_m) || room.randomization_m < 0 || room.randomization_m > 0.5) {
    throw std::invalid_argument("image randomization " + number_text(room.randomization_m) + " m: give 0 to 0.5 m");
  }
}

void check_inside(const ShoeboxRoom& room, const Point3& p, const std::string& what) {
  const double sides[3] = {room.size_m.x, room.size_m.y, room.size_m.z};
  const double at[3] = {p.x, p.y, p.z};
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(at[a]) || at[a] < kMinInsideM || at[a] > sides[a] - kMinInsideM) {
      throw std::invalid_argument(what + " at (" + number_text(p.x) + ", " + number_text(p.y) + ", " +
                                  number_text(p.z) + ") m is not inside the " + number_text(room.size_m.x) + " x " +
                                  number_text(room.size_m.y) + " x " + number_text(room.size_m.z) +
                                  " m room: give a position at least 1 cm from every wall, floor and ceiling");
    }
  }
}

double distance_m(const Point3& a, const Point3& b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

}  // namespace dtmf::sim
