#include "ros_bridge/e2e/ros2_test_endpoints.h"

#include <dds/dds.h>

#include <stdexcept>
#include <thread>

#include "ros2/dds_support.h"
#include "ros2/ros2_msgs.h"

namespace dtmf::test_support {
namespace {

[[noreturn]] void fail(const std::string& step, dds_return_t rc) {
  throw std::runtime_error("ros2 test endpoint: " + step + " failed: " + dds_strretcode(rc));
}

std::int32_t participant_on(int domain) {
  const dds_entity_t p = dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  if (p < 0) fail("creating a participant on domain " + std::to_string(domain), p);
  return p;
}

dds_qos_t* ros_qos(bool reliable) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT, DDS_MSECS(100));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);  // teleop_twist_keyboard's depth
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

std::int32_t writer_on(std::int32_t participant, const dds_topic_descriptor_t* type, const std::string& ros_topic,
                       bool reliable) {
  const std::string name = ros2::dds_topic_name(ros_topic);
  const dds_entity_t topic = dds_create_topic(participant, type, name.c_str(), nullptr, nullptr);
  if (topic < 0) fail("creating topic " + name, topic);
  dds_qos_t* qos = ros_qos(reliable);
  const dds_entity_t writer = dds_create_writer(participant, topic, qos, nullptr);
  dds_delete_qos(qos);
  if (writer < 0) fail("creating a writer on " + name, writer);
  return writer;
}

bool readers_matched(std::int32_t writer, int n, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    dds_publication_matched_status_t status;
    if (dds_get_publication_matched_status(writer, &status) == DDS_RETCODE_OK &&
        static_cast<int>(status.current_count) >= n)
      return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace

TwistPublisher::TwistPublisher(int domain, const std::string& ros_topic, TwistQos qos) : qos_(qos) {
  participant_ = participant_on(domain);
  writer_ = writer_on(participant_,
                      qos.stamped ? &geometry_msgs_msg_dds__TwistStamped__desc : &geometry_msgs_msg_dds__Twist__desc,
                      ros_topic, qos.reliable);
}

TwistPublisher::~TwistPublisher() { dds_delete(participant_); }

void TwistPublisher::publish(double linear_mps, double angular_radps, const std::string& frame_id) {
  geometry_msgs_msg_dds__Twist_ twist{};
  twist.linear.x = linear_mps;
  twist.angular.z = angular_radps;
  dds_return_t rc;
  if (qos_.stamped) {
    geometry_msgs_msg_dds__TwistStamped_ stamped{};
    const ros2::RosTime now = ros2::ros_time(std::chrono::system_clock::now());
    stamped.header.stamp = {now.sec, now.nanosec};
    stamped.header.frame_id = const_cast<char*>(frame_id.c_str());  // dds_write only reads it
    stamped.twist = twist;
    rc = dds_write(writer_, &stamped);
  } else {
    rc = dds_write(writer_, &twist);
  }
  if (rc != DDS_RETCODE_OK) fail("writing a twist", rc);
}

std::chrono::steady_clock::time_point TwistPublisher::hold(double linear_mps, double angular_radps,
                                                           std::chrono::milliseconds duration,
                                                           std::chrono::milliseconds period) {
  const auto start = std::chrono::steady_clock::now();
  auto next = start;
  std::chrono::steady_clock::time_point last;
  while (next - start < duration) {
    publish(linear_mps, angular_radps);
    last = std::chrono::steady_clock::now();
    next += period;
    std::this_thread::sleep_until(next);
  }
  return last;
}

bool TwistPublisher::wait_for_readers(int n, std::chrono::milliseconds timeout) const {
  return readers_matched(writer_, n, timeout);
}

EmptyPublisher::EmptyPublisher(int domain, const std::string& ros_topic) {
  participant_ = participant_on(domain);
  writer_ = writer_on(participant_, &std_msgs_msg_dds__Empty__desc, ros_topic, true);
}

EmptyPublisher::~EmptyPublisher() { dds_delete(participant_); }

void EmptyPublisher::publish() {
  const std_msgs_msg_dds__Empty_ empty{};
  const dds_return_t rc = dds_write(writer_, &empty);
  if (rc != DDS_RETCODE_OK) fail("writing an empty message", rc);
}

bool EmptyPublisher::wait_for_readers(int n, std::chrono::milliseconds timeout) const {
  return readers_matched(writer_, n, timeout);
}

DiagnosticsSubscriber::DiagnosticsSubscriber(int domain) {
  participant_ = participant_on(domain);
  const dds_entity_t topic = dds_create_topic(participant_, &diagnostic_msgs_msg_dds__DiagnosticArray__desc,
                                              "rt/diagnostics", nullptr, nullptr);
  if (topic < 0) fail("creating rt/diagnostics", topic);
  dds_qos_t* qos = ros_qos(true);
  dds_listener_t* listener = dds_create_listener(this);
  dds_lset_data_available(listener, &DiagnosticsSubscriber::on_data_available);
  const dds_entity_t reader = dds_create_reader(participant_, topic, qos, listener);
  dds_delete_listener(listener);
  dds_delete_qos(qos);
  if (reader < 0) fail("creating a reader on rt/diagnostics", reader);
}

DiagnosticsSubscriber::~DiagnosticsSubscriber() { dds_delete(participant_); }

void DiagnosticsSubscriber::on_data_available(std::int32_t reader, void* self) {
  static_cast<DiagnosticsSubscriber*>(self)->take(reader);
}

void DiagnosticsSubscriber::take(std::int32_t reader) {
  constexpr int kBatch = 8;
  void* loans[kBatch] = {};
  dds_sample_info_t infos[kBatch];
  const dds_return_t n = dds_take(reader, loans, infos, kBatch, kBatch);
  if (n <= 0) return;
  {
    std::lock_guard lock(mutex_);
    for (int i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* array = static_cast<const diagnostic_msgs_msg_dds__DiagnosticArray_*>(loans[i]);
      for (std::uint32_t s = 0; s < array->status._length; ++s) {
        const auto& status = array->status._buffer[s];
        ReceivedStatus r{status.level, status.message, {}, std::chrono::steady_clock::now()};
        for (std::uint32_t v = 0; v < status.values._length; ++v)
          r.values[status.values._buffer[v].key] = status.values._buffer[v].value;
        latest_[status.hardware_id] = std::move(r);
      }
    }
  }
  arrived_.notify_all();
  dds_return_loan(reader, loans, n);
}

ReceivedStatus DiagnosticsSubscriber::wait_for(const std::string& robot,
                                               const std::function<bool(const ReceivedStatus&)>& accept,
                                               std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  ReceivedStatus found;
  arrived_.wait_for(lock, timeout, [&] {
    const auto it = latest_.find(robot);
    if (it == latest_.end() || !accept(it->second)) return false;
    found = it->second;
    return true;
  });
  return found;
}

ReceivedStatus DiagnosticsSubscriber::latest(const std::string& robot) const {
  std::lock_guard lock(mutex_);
  const auto it = latest_.find(robot);
  return it == latest_.end() ? ReceivedStatus{} : it->second;
}

}  // namespace dtmf::test_support
