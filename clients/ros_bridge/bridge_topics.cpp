#include "bridge_topics.h"

#include <cctype>
#include <stdexcept>

namespace dtmf::ros_bridge {
namespace {

constexpr std::size_t kMaxNameChars = 64;  // a robot name quoted in an error, at most

bool is_ros_name(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameChars || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}

std::string quoted(const std::string& name) {
  std::string out = "\"";
  for (const char c : name.substr(0, kMaxNameChars)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return out + (name.size() > kMaxNameChars ? "...\"" : "\"");
}

}  // namespace

BridgeTopics bridge_topics(const std::vector<std::string>& robot_names) {
  if (robot_names.empty()) {
    throw std::invalid_argument("the server names no robot (ListRobots): start dtmf-server with --robots");
  }
  BridgeTopics topics;
  for (const std::string& name : robot_names) {
    if (robot_names.size() == 1) {
      topics.robots.push_back({name, "cmd_vel", "cmd_vel_confirmed"});
      continue;
    }
    if (!is_ros_name(name)) {
      throw std::invalid_argument("robot " + quoted(name) +
                                  " cannot name a ROS 2 namespace (a letter, then letters, digits and underscores): "
                                  "rename it in dtmf-server --robots");
    }
    topics.robots.push_back({name, name + "/cmd_vel", name + "/cmd_vel_confirmed"});
  }
  return topics;
}

}  // namespace dtmf::ros_bridge
