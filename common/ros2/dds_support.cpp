#include "ros2/dds_support.h"

#include <dds/dds.h>

#include <charconv>
#include <cstdlib>
#include <type_traits>
#include <vector>

namespace dtmf::ros2 {
namespace {

static_assert(std::is_same_v<dds_entity_t, std::int32_t>, "entities are kept as int32 to keep DDS out of headers");

const char* const kNetworkHint =
    "CycloneDDS logs the cause on stderr; check CYCLONEDDS_URI (its XML, and that the network "
    "interface it names exists and is up)";

int parse_domain_env(std::string_view who, std::string_view s) {
  int value = -1;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || value < 0) {
    throw DdsError(std::string(who) + ": ROS_DOMAIN_ID=\"" + std::string(s.substr(0, 32)) +
                       "\" is not a domain id (a number 0-" + std::to_string(kMaxDomainId) + ")",
                   DDS_RETCODE_BAD_PARAMETER);
  }
  return value;
}

// dds_get_name and dds_get_type_name truncate at the buffer and return the full length.
std::string topic_string(dds_return_t (*get)(dds_entity_t, char*, size_t), dds_entity_t topic, const char* what) {
  std::vector<char> buffer(128);
  for (;;) {
    const dds_return_t n = get(topic, buffer.data(), buffer.size());
    if (n < 0) dds_fail("DDS", std::string("reading the ") + what, n, "");
    if (static_cast<std::size_t>(n) < buffer.size()) return std::string(buffer.data(), static_cast<std::size_t>(n));
    buffer.resize(static_cast<std::size_t>(n) + 1);
  }
}

}  // namespace

void dds_fail(std::string_view who, const std::string& step, int retcode, const std::string& hint) {
  throw DdsError(
      std::string(who) + ": " + step + " failed: " + dds_strretcode(retcode) + (hint.empty() ? "" : ". " + hint),
      retcode);
}

int resolve_domain(std::string_view who, const std::optional<int>& given) {
  int domain = 0;
  if (given) {
    domain = *given;
  } else if (const char* env = std::getenv("ROS_DOMAIN_ID"); env != nullptr && *env != '\0') {
    domain = parse_domain_env(who, env);  // ROS treats an empty ROS_DOMAIN_ID as unset
  }
  // Cast to dds_domainid_t, -1 would be DDS_DOMAIN_DEFAULT and quietly mean "whatever the
  // configuration says" instead of an error.
  if (domain < 0) {
    throw DdsError(std::string(who) + ": domain id " + std::to_string(domain) + " is negative (ROS 2 uses 0-" +
                       std::to_string(kMaxDomainId) + ")",
                   DDS_RETCODE_BAD_PARAMETER);
  }
  return domain;
}

std::string dds_topic_name(std::string_view ros_topic) {
  if (ros_topic.starts_with('/')) ros_topic.remove_prefix(1);
  if (ros_topic.empty()) throw DdsError("DDS: empty topic name", DDS_RETCODE_BAD_PARAMETER);
  return "rt/" + std::string(ros_topic);
}

std::int32_t create_participant(std::string_view who, int domain) {
  const dds_entity_t participant = dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  if (participant < 0) {
    std::string hint = kNetworkHint;
    if (domain > kMaxDomainId) {
      hint = "Domain ids above " + std::to_string(kMaxDomainId) +
             " give UDP ports above 65535 with the default port mapping; ROS 2 uses 0-" + std::to_string(kMaxDomainId) +
             " (TurtleBot3's default is 30). " + hint;
    }
    dds_fail(who, "creating the DDS participant on domain " + std::to_string(domain), participant, hint);
  }
  return participant;
}

RosTime ros_time(std::chrono::system_clock::time_point t) {
  using namespace std::chrono;
  // Floor, not truncation: ROS's nanosec is never negative, also before 1970.
  const auto ns = duration_cast<nanoseconds>(t.time_since_epoch());
  const auto sec = floor<seconds>(ns);
  return {static_cast<std::int32_t>(sec.count()), static_cast<std::uint32_t>((ns - sec).count())};
}

std::string topic_name_of(std::int32_t topic) { return topic_string(dds_get_name, topic, "topic name"); }

std::string type_name_of(std::int32_t topic) { return topic_string(dds_get_type_name, topic, "type name"); }

}  // namespace dtmf::ros2
