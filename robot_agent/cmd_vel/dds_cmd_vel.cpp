#include "cmd_vel/dds_cmd_vel.h"

#include <dds/dds.h>

#include <thread>

#include "ros2/ros2_msgs.h"

namespace dtmf::agent {
namespace {

constexpr std::string_view kWho = "DdsCmdVel";

[[noreturn]] void fail(const std::string& step, dds_return_t rc, const std::string& hint) {
  ros2::dds_fail(kWho, step, rc, hint);
}

geometry_msgs_msg_dds__Twist_ twist(const Velocity& v) {
  geometry_msgs_msg_dds__Twist_ t{};
  t.linear.x = v.linear_mps;
  t.angular.z = v.angular_radps;
  return t;
}

}  // namespace

DdsCmdVel::DdsCmdVel(const DdsOptions& options) : options_(options) {
  const int domain = ros2::resolve_domain(kWho, options.domain_id);
  const std::string topic_name = ros2::dds_topic_name(options.topic);
  participant_ = ros2::create_participant(kWho, domain);

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
  // The sender's ROS 2 bridge may read cmd_vel on this domain: this marks the robot's output
  // so that it is never taken for an operator's and sent back (ros2/dds_support.h).
  dds_qset_userdata(qos, ros2::kAgentCmdVelUserData.data(), ros2::kAgentCmdVelUserData.size());
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  writer_ = dds_create_writer(participant_, topic_, qos, nullptr);
  dds_delete_qos(qos);
  if (writer_ < 0) {
    fail_and_clean_up("creating the DDS writer on \"" + topic_name + "\"", writer_,
                      "The QoS is reliable, volatile, keep-last 10, XCDR1; check CYCLONEDDS_URI");
  }
}

DdsCmdVel::~DdsCmdVel() {
  if (participant_ > 0) dds_delete(participant_);
}

void DdsCmdVel::publish(const Velocity& velocity, double /*audio_ms*/, std::chrono::system_clock::time_point stamp) {
  dds_return_t rc;
  if (options_.stamped) {
    geometry_msgs_msg_dds__TwistStamped_ msg{};
    const ros2::RosTime time = ros2::ros_time(stamp);
    msg.header.stamp = {time.sec, time.nanosec};
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

std::string DdsCmdVel::topic_name() const { return ros2::topic_name_of(topic_); }

std::string DdsCmdVel::type_name() const { return ros2::type_name_of(topic_); }

}  // namespace dtmf::agent
