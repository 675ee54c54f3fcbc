// What the gRPC calls tell the bridge's loop, from gRPC's threads: a queue the calls push to
// and the loop takes from, waking the loop's wait (dds_inputs.h) at each push.
#pragma once

#include <grpcpp/grpcpp.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "dtmf/v1/teleop.pb.h"

namespace dtmf::ros_bridge {

// What the bridge's calls call themselves to the server (x-dtmf-client): a Teleop refused
// because the bridge holds the robot names it.
inline constexpr const char* kBridgeClientName = "dtmf-ros-bridge";

struct BridgeEvent {
  enum class Kind {
    TeleopResponse,  // `response` from robot `robot`'s stream `call`
    TeleopEnded,     // that stream ended with `status`
    StopEnded,       // the stop for every robot finished with `status`
  } kind;
  std::size_t robot = 0;
  std::uint64_t call = 0;
  v1::TeleopResponse response;
  grpc::Status status;
};

class BridgeEvents {
 public:
  explicit BridgeEvents(std::function<void()> wake) : wake_(std::move(wake)) {}
  void push(BridgeEvent event) {
    {
      std::lock_guard lock(mutex_);
      events_.push_back(std::move(event));
    }
    wake_();
  }
  std::vector<BridgeEvent> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
  }

 private:
  std::function<void()> wake_;
  std::mutex mutex_;
  std::vector<BridgeEvent> events_;
};

}  // namespace dtmf::ros_bridge
