// The robots one sender drives, as the operator lists them (dtmf-server --robots FILE).
//
// A JSON array, one object per robot:
//   [{"name": "alpha", "address": 1, "key": "/etc/dtmf-teleop/alpha.key", "model": "burger"},
//    {"name": "beta",  "address": 2}]
// `name` (letters, digits, - and _, up to 32) and `address` (0..7, the robot's
// dtmf-agent --address) are required; `key` (its link key, dtmfctl keygen) and `model`
// (burger, waffle, waffle_pi; default burger) are not. Parsing checks each entry and names
// what is wrong with which; it reads no key. Pure logic.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dtmf::server {

struct RobotEntry {
  std::string name;
  std::uint8_t address = 0;
  std::string key_file;  // empty: no key
  std::string model = "burger";
};

// A robot's name: 1 to 32 letters, digits, - or _ (it goes into logs, rows and flags).
bool robot_name_valid(std::string_view name);

// The robots in `json`; std::invalid_argument naming `origin` (the file), the entry and the
// field for anything wrong: not JSON, not a list, no robot, a missing or bad field, an
// unknown field, two robots with one name or one address.
std::vector<RobotEntry> parse_robots(std::string_view json, const std::string& origin);

}  // namespace dtmf::server
