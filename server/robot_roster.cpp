#include "robot_roster.h"

#include <nlohmann/json.hpp>

#include <stdexcept>

#include "command/robot_model.h"

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

RobotEntry entry_of(const nlohmann::json& item, const std::string& where) {
  if (!item.is_object()) throw std::invalid_argument(where + ": not an object ({\"name\": ..., \"address\": ...})");
  for (const auto& [field, value] : item.items()) {
    if (field != "name" && field != "address" && field != "key" && field != "model")
      throw std::invalid_argument(where + ": unknown field \"" + field + "\" (name, address, key, model)");
  }
  RobotEntry e;
  if (!item.contains("name") || !item["name"].is_string())
    throw std::invalid_argument(where + ": \"name\" is required");
  e.name = item["name"].get<std::string>();
  if (!robot_name_valid(e.name))
    throw std::invalid_argument(where + ": name \"" + e.name + "\": 1 to 32 letters, digits, - or _");
  const std::string named = where + " (" + e.name + ")";
  if (!item.contains("address") || !item["address"].is_number_integer())
    throw std::invalid_argument(named + ": \"address\" is required, a whole number 0..7 (its dtmf-agent --address)");
  const auto address = item["address"].get<long long>();
  if (address < 0 || address > kMaxAddress)
    throw std::invalid_argument(named + ": address " + std::to_string(address) + " is outside 0..7");
  e.address = static_cast<std::uint8_t>(address);
  if (item.contains("key")) {
    if (!item["key"].is_string() || item["key"].get<std::string>().empty())
      throw std::invalid_argument(named + ": \"key\" is the path of its key file (dtmfctl keygen FILE)");
    e.key_file = item["key"].get<std::string>();
  }
  if (item.contains("model")) {
    if (!item["model"].is_string()) throw std::invalid_argument(named + ": \"model\" is burger, waffle or waffle_pi");
    e.model = item["model"].get<std::string>();
    try {
      command::robot_model_by_name(e.model);
    } catch (const std::exception& ex) {
      throw std::invalid_argument(named + ": model: " + ex.what());
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
      if (other.name == e.name) throw std::invalid_argument(origin + ": two robots are called " + e.name);
      if (other.address == e.address)
        throw std::invalid_argument(origin + ": robots " + other.name + " and " + e.name + " share address " +
                                    std::to_string(e.address) + ": give each its own (dtmf-agent --address)");
    }
    robots.push_back(std::move(e));
  }
  return robots;
}

}  // namespace dtmf::server
