// The robots one sender drives, as the operator lists them (dtmf-server --robots FILE).
//
// A JSON array, one object per robot:
//   [{"name": "alpha", "address": 1, "key": "/etc/dtmf-teleop/alpha.key", "model": "burger"},
//    {"name": "beta",  "address": 2}]
// `name` (letters, digits, - and _, up to 32) and `address` (0..7, the robot's
// dtmf-agent --address) are required; `key` (its link key, dtmfctl keygen) and `model`
// (burger, waffle, waffle_pi; default burger) are not. Parsing checks each entry and names
// what is wrong with which, every text from the file shown quoted, escaped and cut
// (shown_text.h); it reads no key. The file decides which key each robot gets, so the server
// reads it only when no one else may change it (secret_file.h, read_trusted_file).
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
// unknown field, a key path holding a control character, two robots with one name or one
// address.
std::vector<RobotEntry> parse_robots(std::string_view json, const std::string& origin);

// The robots in the file `path` (dtmf-server --robots): read only if no one but its owner, this
// user or root, may change it, and not through a symbolic link (read_trusted_file,
// secret_file.h), then parse_robots. Throws SecretFileError or std::invalid_argument.
std::vector<RobotEntry> read_robots(const std::string& path);

// Reads every robot's key file and the room key's (empty: none), and refuses, with
// std::invalid_argument naming `origin` and both entries, two robots under one key (one file
// named twice, or one key in two files) and a robot whose key is the room key. Opens no
// counter store: run before link_options(), the refusal says what is wrong, not that a
// counter is locked. Key files' own refusals (security/link_key.h) pass through.
void check_keys_apart(const std::vector<RobotEntry>& robots, const std::string& room_key_file,
                      const std::string& origin);

}  // namespace dtmf::server
