#include "cmd_vel/dds_cmd_vel.h"

#include <dds/dds.h>

#include <charconv>
#include <cstdlib>
#include <thread>
#include <type_traits>
#include <vector>

#include "cmd_vel/ros2_msgs.h"

namespace dtmf::agent {
namespace {

static_assert(std::is_same_v<dds_entity_t, std::int32_t>, "DdsCmdVel::Entity must hold a dds_entity_t");

// Above this, DDS's default port mapping (7400 + 250 * domain + ...) leaves the 16-bit
// port range; ROS 2 documents the same bound.
constexpr int kMaxDomainId = 232;

const char* const kNetworkHint =
    "CycloneDDS logs the cause on stderr; check CYCLONEDDS_URI (its XML, and that the network "
    "interface it names exists and is up)";

[[noreturn]] void fail(const std::string& step, dds_return_t rc, const std::string& hint) {
  throw DdsError("DdsCmdVel: " + step + " failed: " + dds_strretcode(rc) + (hint.empty() ? "" : ". " + hint), rc);
}

int parse_domain_env(const char* text) {
  const std::string_view s(text);
  int value = -1;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || value < 0) {
    throw DdsError("DdsCmdVel: ROS_DOMAIN_ID=\"" + std::string(s) + "\" is not a domain id (a number 0-" +
                       std::to_string(kMaxDomainId) + ")",
                   DDS_RETCODE_BAD_PARAMETER);
  }
  return value;
}

int resolve_domain(const std::optional<int>& given) {
  int domain = 0;
  if (given) {
    domain = *given;
  } else if (const char* env = std::getenv("ROS_DOMAIN_ID"); env != nullptr && *env != '\0') {
    domain = parse_domain_env(env);  // ROS treats an empty ROS_DOMAIN_ID as unset
  }
  // Cast to dds_domainid_t, -1 would be DDS_DOMAIN_DEFAULT and quietly mean "whatever the
  // configuration says" instead of an error.
  if (domain < 0) {
    throw DdsError("DdsCmdVel: domain id " + std::to_string(domain) + " is negative (ROS 2 uses 0-" +
                       std::to_string(kMaxDomainId) + ")",
                   DDS_RETCODE_BAD_PARAMETER);
  }
  return domain;
}

builtin_interfaces_msg_dds__Time_ ros_time(std::chrono::system_clock::time_point t) {
  using namespace std::chrono;
  // Floor, not truncation: ROS's nanosec is never negative, also before 1970.
  const auto ns = duration_cast<nanoseconds>(t.time_since_epoch());
  const auto sec = floor<seconds>(ns);
  return {static_cast<std::int32_t>(sec.count()), static_cast<std::uint32_t>((ns - sec).count())};
}

// dds_get_name and dds_get_type_name truncate at the buffer and return the full length.
std::string topic_string(dds_return_t (*get)(dds_entity_t, char*, size_t), dds_entity_t topic, const char* what) {
  std::vector<char> buffer(128);
  for (;;) {
    const dds_return_t n = get(topic, buffer.data(), buffer.size());
    if (n < 0) fail(std::string("reading the ") + what, n, "");
    if (static_cast<std::size_t>(n) < buffer.size()) return std::string(buffer.data(), static_cast<std::size_t>(n));
    buffer.resize(static_cast<std::size_t>(n) + 1);
  }
}

geometry_msgs_msg_dds__Twist_ twist(const Velocity& v) {
  geometry_msgs_msg_dds__Twist_ t{};
  t.linear.x = v.linear_mps;
  t.angular.z = v.angular_radps;
  return t;
}

}  // namespace

std::string dds_topic_name(std::string_view ros_topic) {
  if (ros_topic.starts_with('/')) ros_topic.remove_prefix(1);
  if (ros_topic.empty()) {
    throw DdsError("DdsCmdVel: empty topic name", DDS_RETCODE_BAD_PARAMETER);
  }
  return "rt/" + std::string(ros_topic);
}

DdsCmdVel::DdsCmdVel(const DdsOptions& options) : options_(options) {
  const int domain = resolve_domain(options.domain_id);
  const std::string topic_name = dds_topic_name(options.topic);

  participant_ = dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  if (participant_ < 0) {
    const dds_return_t rc = participant_;
    participant_ = 0;
    std::string hint = kNetworkHint;
    if (domain > kMaxDomainId) {
      hint = "Domain ids above " + std::to_string(kMaxDomainId) +
             " give UDP ports above 65535 with the default port mapping; ROS 2 uses 0-" + std::to_string(kMaxDomainId) +
             " (TurtleBot3's default is 30). " + hint;
    }
    fail("creating the DDS participant on domain " + std::to_string(domain), rc, hint);
  }

  // The destructor does not run when the constructor throws, and deleting the participant
  // deletes whatever was created in it.
  auto fail_and_clean_up = [this](const std::string& step, dds_return_t rc, const std::string& hint) {
    dds_delete(participant_);
    participant_ = 0;
    fail(step, rc, hint);
  };

  const dds_topic_descriptor_t* type =
      options.stamped ? &geometry_msgs_msg_dds__TwistStamped__desc : &geometry_msgs_msg_dds__Twist__desc;
  topic_ = dds_create_topic(participant_, type, topic_name.c_str(), nullptr, nullptr);
  if (topic_ < 0) {
    fail_and_clean_up("creating DDS topic \"" + topic_name + "\" (" + type->m_typename + ")", topic_,
                      "Check that \"" + options.topic + "\" is a valid ROS topic name");
  }

  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE,
                       DDS_MSECS(100));               // a stuck network must not stall the agent for long
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);  // a late robot must not act on stale velocities
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  writer_ = dds_create_writer(participant_, topic_, qos, nullptr);
  dds_delete_qos(qos);
  if (writer_ < 0) {
    fail_and_clean_up("creating the DDS writer on \"" + topic_name + "\"", writer_,
                      "The QoS is reliable, volatile, keep-last 10, XCDR1; " + std::string(kNetworkHint));
  }
}

DdsCmdVel::~DdsCmdVel() {
  if (participant_ > 0) dds_delete(participant_);
}

void DdsCmdVel::publish(const Velocity& velocity, double /*audio_ms*/, std::chrono::system_clock::time_point stamp) {
  dds_return_t rc;
  if (options_.stamped) {
    geometry_msgs_msg_dds__TwistStamped_ msg{};
    msg.header.stamp = ros_time(stamp);
    msg.header.frame_id = const_cast<char*>(options_.frame_id.c_str());  // dds_write only reads it
    msg.twist = twist(velocity);
    rc = dds_write(writer_, &msg);
  } else {
    const geometry_msgs_msg_dds__Twist_ msg = twist(velocity);
    rc = dds_write(writer_, &msg);
  }
  if (rc != DDS_RETCODE_OK) {
    fail("writing to \"" + topic_name() + "\"", rc, "The velocity was not sent");
  }
}

int DdsCmdVel::matched_subscribers() const {
  dds_publication_matched_status_t status;
  const dds_return_t rc = dds_get_publication_matched_status(writer_, &status);
  if (rc != DDS_RETCODE_OK) fail("reading the matched status", rc, "");
  return static_cast<int>(status.current_count);
}

bool DdsCmdVel::wait_for_subscribers(int n, std::chrono::milliseconds timeout) const {
  // Polls rather than waits on the status condition: reading the matched status (as
  // matched_subscribers() does) resets its "changed" flag, so a waitset could miss a match.
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (matched_subscribers() < n) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

int DdsCmdVel::domain_id() const {
  dds_domainid_t id = 0;
  const dds_return_t rc = dds_get_domainid(participant_, &id);
  if (rc != DDS_RETCODE_OK) fail("reading the domain id", rc, "");
  return static_cast<int>(id);
}

std::string DdsCmdVel::topic_name() const { return topic_string(dds_get_name, topic_, "topic name"); }

std::string DdsCmdVel::type_name() const { return topic_string(dds_get_type_name, topic_, "type name"); }

}  // namespace dtmf::agent
