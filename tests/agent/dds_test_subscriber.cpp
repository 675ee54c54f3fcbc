#include "agent/dds_test_subscriber.h"

#include <dds/dds.h>

#include <cstring>
#include <stdexcept>

#include "ros2/dds_support.h"
#include "ros2/ros2_msgs.h"

namespace dtmf::test_support {
namespace {

[[noreturn]] void fail(const std::string& step, dds_return_t rc) {
  throw std::runtime_error("CmdVelSubscriber: " + step + " failed: " + dds_strretcode(rc));
}

ReceivedCmdVel::Vector3 vector3(const geometry_msgs_msg_dds__Vector3_& v) { return {v.x, v.y, v.z}; }

}  // namespace

CmdVelSubscriber::CmdVelSubscriber(int domain_id, const std::string& dds_topic, bool stamped) : stamped_(stamped) {
  participant_ = dds_create_participant(static_cast<dds_domainid_t>(domain_id), nullptr, nullptr);
  if (participant_ < 0) fail("creating the participant on domain " + std::to_string(domain_id), participant_);

  const dds_topic_descriptor_t* type =
      stamped ? &geometry_msgs_msg_dds__TwistStamped__desc : &geometry_msgs_msg_dds__Twist__desc;
  const dds_entity_t topic = dds_create_topic(participant_, type, dds_topic.c_str(), nullptr, nullptr);
  if (topic < 0) {
    dds_delete(participant_);
    fail("creating topic " + dds_topic, topic);
  }

  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  dds_listener_t* listener = dds_create_listener(this);
  dds_lset_data_available(listener, &CmdVelSubscriber::on_data_available);
  const dds_entity_t reader = dds_create_reader(participant_, topic, qos, listener);
  dds_delete_listener(listener);  // the reader keeps its own copy
  dds_delete_qos(qos);
  if (reader < 0) {
    dds_delete(participant_);
    fail("creating the reader on " + dds_topic, reader);
  }
  reader_ = reader;
}

CmdVelSubscriber::~CmdVelSubscriber() {
  // Waits for a listener call in progress, so none touches this object after it is gone.
  dds_delete(participant_);
}

void CmdVelSubscriber::on_data_available(std::int32_t reader, void* self) {
  static_cast<CmdVelSubscriber*>(self)->take(reader);
}

void CmdVelSubscriber::take(std::int32_t reader) {
  constexpr int kBatch = 16;
  void* loans[kBatch] = {};  // null: Cyclone lends its own samples
  dds_sample_info_t infos[kBatch];
  for (;;) {
    const dds_return_t n = dds_take(reader, loans, infos, kBatch, kBatch);
    if (n <= 0) return;
    const auto now = std::chrono::steady_clock::now();
    {
      std::lock_guard lock(mutex_);
      for (int i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;  // e.g. a writer going away
        ReceivedCmdVel r;
        if (stamped_) {
          const auto* m = static_cast<const geometry_msgs_msg_dds__TwistStamped_*>(loans[i]);
          r.linear = vector3(m->twist.linear);
          r.angular = vector3(m->twist.angular);
          r.stamp_sec = m->header.stamp.sec;
          r.stamp_nanosec = m->header.stamp.nanosec;
          r.frame_id = m->header.frame_id != nullptr ? m->header.frame_id : "";
        } else {
          const auto* m = static_cast<const geometry_msgs_msg_dds__Twist_*>(loans[i]);
          r.linear = vector3(m->linear);
          r.angular = vector3(m->angular);
        }
        r.received = now;
        r.from_agent = written_by_agent(reader, infos[i].publication_handle);
        samples_.push_back(std::move(r));
      }
    }
    arrived_.notify_all();
    dds_return_loan(reader, loans, n);
  }
}

bool CmdVelSubscriber::written_by_agent(std::int32_t reader, std::uint64_t publication) const {
  dds_builtintopic_endpoint_t* writer = dds_get_matched_publication_data(reader, publication);
  if (writer == nullptr) return false;
  void* data = nullptr;
  size_t size = 0;
  const bool agent = dds_qget_userdata(writer->qos, &data, &size) && size == ros2::kAgentCmdVelUserData.size() &&
                     std::memcmp(data, ros2::kAgentCmdVelUserData.data(), size) == 0;
  dds_free(data);
  dds_builtintopic_free_endpoint(writer);
  return agent;
}

bool CmdVelSubscriber::wait_for(std::size_t count, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return arrived_.wait_for(lock, timeout, [&] { return samples_.size() >= count; });
}

std::vector<ReceivedCmdVel> CmdVelSubscriber::samples() const {
  std::lock_guard lock(mutex_);
  return samples_;
}

int CmdVelSubscriber::matched_publishers() const {
  dds_subscription_matched_status_t status;
  const dds_return_t rc = dds_get_subscription_matched_status(reader_, &status);
  if (rc != DDS_RETCODE_OK) fail("reading the matched status", rc);
  return static_cast<int>(status.current_count);
}

}  // namespace dtmf::test_support
