#include "dds_inputs.h"

#include <dds/dds.h>

#include <cmath>
#include <cstring>

#include "ros2/dds_support.h"
#include "ros2/ros2_msgs.h"

namespace dtmf::ros_bridge {
namespace {

constexpr std::string_view kWho = "dtmf-ros-bridge";
constexpr int kReaderDepth = 16;
constexpr std::uint32_t kTakeAtOnce = 32;

void check(dds_return_t rc, const std::string& step) {
  if (rc < 0) ros2::dds_fail(kWho, step, rc, "check CYCLONEDDS_URI and the domain");
}

dds_qos_t* reader_qos() {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_BEST_EFFORT, 0);
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);  // a velocity from before the bridge started is stale
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, kReaderDepth);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

}  // namespace

DdsInputs::DdsInputs(int domain, const BridgeTopics& topics) : skipped_from_agent_(topics.robots.size(), 0) {
  participant_ = ros2::create_participant(kWho, domain);
  try {
    waitset_ = dds_create_waitset(DDS_CYCLONEDDS_HANDLE);
    check(waitset_, "creating the waitset");
    guard_ = dds_create_guardcondition(DDS_CYCLONEDDS_HANDLE);
    check(guard_, "creating the guard condition");
    check(dds_waitset_attach(waitset_, guard_, guard_), "attaching the guard condition");
    for (std::size_t i = 0; i < topics.robots.size(); ++i) {
      add_reader(&geometry_msgs_msg_dds__TwistStamped__desc, topics.robots[i].cmd_vel, i);
      add_reader(&geometry_msgs_msg_dds__Twist__desc, topics.robots[i].cmd_vel, i);
    }
    add_reader(&std_msgs_msg_dds__Empty__desc, topics.stop_every_robot, 0);
  } catch (...) {
    release();  // the destructor does not run when the constructor throws
    throw;
  }
}

DdsInputs::~DdsInputs() { release(); }

void DdsInputs::release() {
  // Deleting a participant deletes its topics, readers and conditions.
  for (dds_entity_t* e : {&waitset_, &guard_, &participant_}) {
    if (*e > 0) dds_delete(*e);
    *e = 0;
  }
}

void DdsInputs::add_reader(const void* type, const std::string& ros_topic, std::size_t robot) {
  const auto* descriptor = static_cast<const dds_topic_descriptor_t*>(type);
  const std::string name = ros2::dds_topic_name(ros_topic);
  const dds_entity_t topic = dds_create_topic(participant_, descriptor, name.c_str(), nullptr, nullptr);
  check(topic, "creating DDS topic \"" + name + "\" (" + descriptor->m_typename + ")");
  dds_qos_t* qos = reader_qos();
  const dds_entity_t reader = dds_create_reader(participant_, topic, qos, nullptr);
  dds_delete_qos(qos);
  check(reader, "creating a reader on \"" + name + "\"");
  const dds_entity_t condition = dds_create_readcondition(reader, DDS_ANY_STATE);
  check(condition, "creating a read condition on \"" + name + "\"");
  check(dds_waitset_attach(waitset_, condition, reader), "waiting on \"" + name + "\"");
  if (descriptor == &std_msgs_msg_dds__Empty__desc) {
    stop_reader_ = reader;
  } else {
    twist_readers_.push_back({reader, robot, descriptor == &geometry_msgs_msg_dds__TwistStamped__desc});
  }
}

void DdsInputs::wait(double timeout_ms) {
  const dds_duration_t timeout = timeout_ms <= 0 ? 0 : static_cast<dds_duration_t>(std::ceil(timeout_ms * 1e6));
  dds_attach_t triggered[8];
  check(dds_waitset_wait(waitset_, triggered, 8, timeout), "waiting for DDS");
  bool was_set = false;
  dds_take_guardcondition(guard_, &was_set);
}

void DdsInputs::wake() { dds_set_guardcondition(guard_, true); }

DdsInputs::Writer DdsInputs::writer_of(std::int32_t reader, std::uint64_t publication) {
  if (const auto known = writers_.find(publication); known != writers_.end()) return known->second;
  dds_builtintopic_endpoint_t* endpoint = dds_get_matched_publication_data(reader, publication);
  if (endpoint == nullptr) return Writer::Unknown;  // not yet described: asked again next time
  void* data = nullptr;
  size_t size = 0;
  Writer writer = Writer::Operator;
  if (dds_qget_userdata(endpoint->qos, &data, &size) && size == ros2::kAgentCmdVelUserData.size() &&
      std::memcmp(data, ros2::kAgentCmdVelUserData.data(), size) == 0) {
    writer = Writer::Agent;
  }
  dds_free(data);
  dds_builtintopic_free_endpoint(endpoint);
  writers_.emplace(publication, writer);
  return writer;
}

std::vector<DdsInputs::Heard> DdsInputs::take_twists() {
  std::vector<Heard> heard;
  for (const Reader& r : twist_readers_) {
    void* samples[kTakeAtOnce] = {};
    dds_sample_info_t infos[kTakeAtOnce];
    const dds_return_t n = dds_take(r.reader, samples, infos, kTakeAtOnce, kTakeAtOnce);
    check(n, "taking cmd_vel");
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const Writer writer = writer_of(r.reader, infos[i].publication_handle);
      if (writer != Writer::Operator) {
        if (writer == Writer::Agent) ++skipped_from_agent_[r.robot];
        continue;
      }
      const geometry_msgs_msg_dds__Twist_& t =
          r.stamped ? static_cast<const geometry_msgs_msg_dds__TwistStamped_*>(samples[i])->twist
                    : *static_cast<const geometry_msgs_msg_dds__Twist_*>(samples[i]);
      heard.push_back({r.robot, {t.linear.x, t.angular.z}});
    }
    if (n > 0) dds_return_loan(r.reader, samples, n);
  }
  return heard;
}

bool DdsInputs::take_stop_every_robot() {
  void* samples[kTakeAtOnce] = {};
  dds_sample_info_t infos[kTakeAtOnce];
  const dds_return_t n = dds_take(stop_reader_, samples, infos, kTakeAtOnce, kTakeAtOnce);
  check(n, "taking stop_every_robot");
  bool stop = false;
  for (dds_return_t i = 0; i < n; ++i) {
    stop = stop || (infos[i].valid_data && writer_of(stop_reader_, infos[i].publication_handle) != Writer::Agent);
  }
  if (n > 0) dds_return_loan(stop_reader_, samples, n);
  return stop;
}

}  // namespace dtmf::ros_bridge
