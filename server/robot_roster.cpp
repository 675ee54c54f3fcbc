#include "robot_roster.h"

#include <openssl/crypto.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <climits>
#include <memory>
#include <stdexcept>

#include "command/robot_model.h"
#include "secret_file.h"
#include "security/link_key.h"
#include "shown_text.h"

namespace dtmf::server {

namespace {

constexpr std::size_t kMaxNameChars = 32;
constexpr int kMaxAddress = 7;

}  // namespace

bool robot_name_valid(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameChars) return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (!ok) return false;
  }
  return true;
}

namespace {

// The key file's path, refused when it could not be a path or would break the lines that
// name it (key files' own errors, security/link_key.cpp, print it as it is).
std::string key_path_of(const nlohmann::json& key, const std::string& named) {
  if (!key.is_string() || key.get<std::string>().empty())
    throw std::invalid_argument(named + ": \"key\" is the path of its key file (dtmfctl keygen FILE)");
  const std::string path = key.get<std::string>();
  const bool control = std::any_of(path.begin(), path.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 || byte == 0x7f;
  });
  if (control || path.size() >= PATH_MAX)
    throw std::invalid_argument(named + ": key " + shown(path) + ": " +
                                (control ? "holds a control character" : "is longer than any path") +
                                "; name its key file by a plain path");
  return path;
}

RobotEntry entry_of(const nlohmann::json& item, const std::string& where) {
  if (!item.is_object()) throw std::invalid_argument(where + ": not an object ({\"name\": ..., \"address\": ...})");
  for (const auto& [field, value] : item.items()) {
    if (field != "name" && field != "address" && field != "key" && field != "model")
      throw std::invalid_argument(where + ": unknown field " + shown(field) + " (name, address, key, model)");
  }
  RobotEntry e;
  if (!item.contains("name") || !item["name"].is_string())
    throw std::invalid_argument(where + ": \"name\" is required");
  e.name = item["name"].get<std::string>();
  if (!robot_name_valid(e.name))
    throw std::invalid_argument(where + ": name " + shown(e.name) + ": 1 to 32 letters, digits, - or _");
  const std::string named = where + " " + shown(e.name);
  if (!item.contains("address") || !item["address"].is_number_integer())
    throw std::invalid_argument(named + ": \"address\" is required, a whole number 0..7 (its dtmf-agent --address)");
  const auto address = item["address"].get<long long>();
  if (address < 0 || address > kMaxAddress)
    throw std::invalid_argument(named + ": address " + std::to_string(address) + " is outside 0..7");
  e.address = static_cast<std::uint8_t>(address);
  if (item.contains("key")) e.key_file = key_path_of(item["key"], named);
  if (item.contains("model")) {
    if (!item["model"].is_string()) throw std::invalid_argument(named + ": \"model\" is burger, waffle or waffle_pi");
    e.model = item["model"].get<std::string>();
    try {
      command::robot_model_by_name(e.model);
    } catch (const std::invalid_argument&) {  // its text holds the name as it is: not shown
      throw std::invalid_argument(named + ": model " + shown(e.model) + " is none of burger, waffle, waffle_pi");
    }
  }
  return e;
}

}  // namespace

std::vector<RobotEntry> parse_robots(std::string_view json, const std::string& origin) {
  const auto doc = nlohmann::json::parse(json, nullptr, false);
  if (doc.is_discarded()) throw std::invalid_argument(origin + ": not JSON (a list of robots: [{\"name\": ...}])");
  if (!doc.is_array()) throw std::invalid_argument(origin + ": not a list of robots ([{\"name\": ...}, ...])");
  if (doc.empty()) throw std::invalid_argument(origin + ": lists no robot");
  std::vector<RobotEntry> robots;
  for (std::size_t i = 0; i < doc.size(); ++i) {
    RobotEntry e = entry_of(doc[i], origin + ": robot " + std::to_string(i + 1));
    for (const RobotEntry& other : robots) {
      if (other.name == e.name) throw std::invalid_argument(origin + ": two robots are called " + shown(e.name));
      if (other.address == e.address)
        throw std::invalid_argument(origin + ": robots " + shown(other.name) + " and " + shown(e.name) +
                                    " share address " + std::to_string(e.address) +
                                    ": give each its own (dtmf-agent --address)");
    }
    robots.push_back(std::move(e));
  }
  return robots;
}

std::vector<RobotEntry> read_robots(const std::string& path) {
  static constexpr TrustedFile kRobotsFile{"robots", "--robots", "which key each robot gets"};
  return parse_robots(read_trusted_file(path, kRobotsFile), path);
}

namespace {

using Key = std::shared_ptr<const security::LinkKey>;

bool same_key(const Key& a, const Key& b) {
  return a && b && CRYPTO_memcmp(a->bytes().data(), b->bytes().data(), security::kKeyBytes) == 0;
}

// "key id 1a2b3c4d, from "/k/a.key"": which key, and where it was read.
std::string key_named(const Key& key, const std::string& file) {
  return "key id " + key->id_hex() + ", from " + shown(file);
}

// The two robots' keys, one file named twice said once.
std::string keys_named(const Key& key, const std::string& file, const std::string& other_file) {
  if (file == other_file) return key_named(key, file) + " for both";
  return key_named(key, file) + "; " + key_named(key, other_file);
}

}  // namespace

void check_keys_apart(const std::vector<RobotEntry>& robots, const std::string& room_key_file,
                      const std::string& origin) {
  const Key room = room_key_file.empty() ? nullptr : security::LinkKey::load(room_key_file);
  std::vector<Key> keys;
  for (const RobotEntry& r : robots) {
    const Key key = r.key_file.empty() ? nullptr : security::LinkKey::load(r.key_file);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (!same_key(keys[i], key)) continue;
      // Why not share one: the sender's freshness counter is kept per key (counter_file.h).
      throw std::invalid_argument(
          origin + ": robots " + shown(robots[i].name) + " and " + shown(r.name) + " have one key (" +
          keys_named(key, robots[i].key_file, r.key_file) +
          "): a key is one robot's alone. Whoever holds it could drive both, and the sender keeps one freshness "
          "counter per key, which two robots cannot share. Make each its own: dtmfctl keygen FILE");
    }
    if (same_key(room, key)) {
      // Every robot of the room holds the room key (docs/security.md, "The room key").
      throw std::invalid_argument(origin + ": robot " + shown(r.name) + " has the room key as its own (" +
                                  key_named(key, r.key_file) + "; --room-key " + shown(room_key_file) +
                                  "): every robot of the room holds the room key, so any of them could drive " +
                                  shown(r.name) + ". Give it a key of its own: dtmfctl keygen FILE");
    }
    keys.push_back(key);
  }
}

}  // namespace dtmf::server
