#include "sim/room_spec.h"

#include <cmath>
#include <stdexcept>

#include "sim/number_text.h"

namespace dtmf::sim {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

bool number(const std::string& text, double& value) {
  try {
    std::size_t end = 0;
    value = std::stod(text, &end);
    return end == text.size() && std::isfinite(value);
  } catch (const std::exception&) {
    return false;
  }
}

Point3 three(const std::string& text, char separator, const std::string& what, const std::string& example) {
  const auto parts = split(text, separator);
  double v[3];
  if (parts.size() != 3 || !number(parts[0], v[0]) || !number(parts[1], v[1]) || !number(parts[2], v[2])) {
    throw std::invalid_argument(what + " '" + text + "' is not three numbers in metres: write it like " + example);
  }
  return {v[0], v[1], v[2]};
}

}  // namespace

Point3 parse_room_size(const std::string& text) {
  Point3 size = three(text, 'x', "room size", "7x9x3");
  for (double side : {size.x, size.y, size.z}) {
    if (side < kMinRoomSideM || side > kMaxRoomSideM) {
      throw std::invalid_argument("room size '" + text + "': every side must lie between 0.5 and 200 m, e.g. 7x9x3");
    }
  }
  return size;
}

Point3 parse_position(const std::string& text) { return three(text, ',', "position", "1.5,2,0.05"); }

std::pair<double, double> parse_range(const std::string& text) {
  const auto parts = split(text, ':');
  double lo = 0, hi = 0;
  if (parts.size() != 2 || !number(parts[0], lo) || !number(parts[1], hi) || !(lo > 0) || !(hi > lo)) {
    throw std::invalid_argument("range '" + text + "' is not MIN:MAX metres with 0 < MIN < MAX, e.g. 0.5:20");
  }
  return {lo, hi};
}

std::vector<Surface> apply_reflection(ShoeboxRoom& room, const std::string& text) {
  std::vector<Surface> surfaces = {kWallX0, kWallX1, kWallY0, kWallY1, kCeiling};
  std::string values = text;
  if (const auto eq = text.find('='); eq != std::string::npos) {
    surfaces.clear();
    values = text.substr(eq + 1);
    for (const std::string& name : split(text.substr(0, eq), '+')) {
      if (name == "walls")
        surfaces.insert(surfaces.end(), {kWallX0, kWallX1, kWallY0, kWallY1});
      else if (name == "all")
        surfaces.insert(surfaces.end(), {kWallX0, kWallX1, kWallY0, kWallY1, kFloor, kCeiling});
      else if (name == "floor")
        surfaces.push_back(kFloor);
      else if (name == "ceiling")
        surfaces.push_back(kCeiling);
      else if (name == "x0")
        surfaces.push_back(kWallX0);
      else if (name == "x1")
        surfaces.push_back(kWallX1);
      else if (name == "y0")
        surfaces.push_back(kWallY0);
      else if (name == "y1")
        surfaces.push_back(kWallY1);
      else {
        throw std::invalid_argument(
            "reflection '" + text + "': no surface '" + name +
            "' (walls, ceiling, floor, x0, x1, y0, y1, all; join with +, e.g. walls+ceiling=0.8)");
      }
    }
  }
  BandValues bands;
  double single = 0;
  if (values.find(':') == std::string::npos) {
    if (!number(values, single)) {
      throw std::invalid_argument("reflection '" + text + "': '" + values +
                                  "' is not a coefficient such as 0.9 or per band 125:0.7,4000:0.9");
    }
    bands = uniform_bands(single);
  } else {
    std::vector<std::pair<double, double>> points;
    for (const std::string& pair : split(values, ',')) {
      const auto parts = split(pair, ':');
      double hz = 0, r = 0;
      if (parts.size() != 2 || !number(parts[0], hz) || !number(parts[1], r) || !(hz > 0)) {
        throw std::invalid_argument("reflection '" + text + "': '" + pair + "' is not Hz:coefficient, e.g. 4000:0.9");
      }
      points.emplace_back(hz, r);
    }
    bands = bands_from_points(points);
  }
  for (std::size_t b = 0; b < kOctaveBands; ++b) {
    if (!(bands[b] >= 0 && bands[b] < 1)) {
      throw std::invalid_argument("reflection '" + text + "': coefficient " + number_text(bands[b]) + " at " +
                                  band_name(b) + " is outside [0, 1) (0.9 a furnished wall, 0.97 a hard floor)");
    }
  }
  for (Surface s : surfaces) room.reflection[s] = bands;
  return surfaces;
}

}  // namespace dtmf::sim
