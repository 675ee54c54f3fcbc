#include "dds_outputs.h"

#include <dds/dds.h>

#include "ros2/dds_support.h"
#include "ros2/ros2_msgs.h"

namespace dtmf::ros_bridge {
namespace {

constexpr std::string_view kWho = "dtmf-ros-bridge";

std::int32_t create_writer(std::int32_t participant, const dds_topic_descriptor_t* type, const std::string& ros_topic) {
  const std::string name = ros2::dds_topic_name(ros_topic);
  const dds_entity_t topic = dds_create_topic(participant, type, name.c_str(), nullptr, nullptr);
  if (topic < 0) ros2::dds_fail(kWho, "creating DDS topic \"" + name + "\" (" + type->m_typename + ")", topic, "");
  dds_qos_t* qos = dds_create_qos();
  // A slow subscriber must not hold up the bridge's loop for long.
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(20));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  const dds_entity_t writer = dds_create_writer(participant, topic, qos, nullptr);
  dds_delete_qos(qos);
  if (writer < 0) ros2::dds_fail(kWho, "creating a writer on \"" + name + "\"", writer, "check CYCLONEDDS_URI");
  return writer;
}

builtin_interfaces_msg_dds__Time_ stamp_of(std::chrono::system_clock::time_point t) {
  const ros2::RosTime time = ros2::ros_time(t);
  return {time.sec, time.nanosec};
}

// dds_write only reads the strings it is given.
char* text(const std::string& s) { return const_cast<char*>(s.c_str()); }

}  // namespace

DdsOutputs::DdsOutputs(std::int32_t participant, const BridgeTopics& topics) {
  diagnostics_writer_ = create_writer(participant, &diagnostic_msgs_msg_dds__DiagnosticArray__desc, topics.diagnostics);
  for (const RobotTopics& robot : topics.robots) {
    confirmed_writers_.push_back(
        create_writer(participant, &geometry_msgs_msg_dds__TwistStamped__desc, robot.cmd_vel_confirmed));
  }
}

void DdsOutputs::publish_diagnostics(const std::vector<RobotHealth>& robots,
                                     std::chrono::system_clock::time_point stamp) {
  // The strings below must outlive dds_write: they are built first, then pointed at.
  std::vector<std::string> names;
  for (const RobotHealth& r : robots) names.push_back("dtmf-teleop: link to " + r.robot);
  std::vector<std::vector<diagnostic_msgs_msg_dds__KeyValue_>> values(robots.size());
  std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> statuses(robots.size());
  for (std::size_t i = 0; i < robots.size(); ++i) {
    for (const auto& [key, value] : robots[i].report.values) values[i].push_back({text(key), text(value)});
    auto& s = statuses[i];
    s.level = static_cast<std::uint8_t>(robots[i].report.level);
    s.name = text(names[i]);
    s.message = text(robots[i].report.message);
    s.hardware_id = text(robots[i].robot);
    s.values = {static_cast<std::uint32_t>(values[i].size()), static_cast<std::uint32_t>(values[i].size()),
                values[i].data(), false};
  }
  diagnostic_msgs_msg_dds__DiagnosticArray_ message{};
  message.header.stamp = stamp_of(stamp);
  message.header.frame_id = const_cast<char*>("");
  message.status = {static_cast<std::uint32_t>(statuses.size()), static_cast<std::uint32_t>(statuses.size()),
                    statuses.data(), false};
  const dds_return_t rc = dds_write(diagnostics_writer_, &message);
  if (rc != DDS_RETCODE_OK) ros2::dds_fail(kWho, "writing /diagnostics", rc, "");
}

void DdsOutputs::publish_confirmed(std::size_t robot, Twist confirmed, std::chrono::system_clock::time_point stamp) {
  geometry_msgs_msg_dds__TwistStamped_ message{};
  message.header.stamp = stamp_of(stamp);
  message.header.frame_id = const_cast<char*>("");
  message.twist.linear.x = confirmed.linear_mps;
  message.twist.angular.z = confirmed.angular_radps;
  const dds_return_t rc = dds_write(confirmed_writers_.at(robot), &message);
  if (rc != DDS_RETCODE_OK) ros2::dds_fail(kWho, "writing cmd_vel_confirmed", rc, "");
}

}  // namespace dtmf::ros_bridge
