// What the bridge reads from ROS 2 over DDS: each robot's cmd_vel, as Twist and as
// TwistStamped, and the stop for every robot (std_msgs/Empty); and the one place its loop
// waits, for a message or for wake() (a DDS waitset with a guard condition).
//
// Readers are BEST_EFFORT, VOLATILE, KEEP_LAST 16, XCDR1: a best-effort reader matches every
// writer, RELIABLE or not, as ROS 2's tools have them (teleop_twist_keyboard: RELIABLE, keep
// last 10), and 16 deep keeps a single key press that arrives with other writers' samples.
// Twist and TwistStamped are read on the same topic name at once, as two DDS topics of one
// participant (CycloneDDS keeps a topic per name and type).
//
// The robot's own output is never taken: the agent's cmd_vel writer carries
// ros2::kAgentCmdVelUserData, and a sample from such a writer is skipped (counted). A sample
// whose writer discovery has not yet described is skipped too, except on the stop's topic,
// where taking it is the safe side.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "bridge_topics.h"
#include "twist_input.h"

namespace dtmf::ros_bridge {

class DdsInputs {
 public:
  // Throws ros2::DdsError when DDS cannot start.
  DdsInputs(int domain, const BridgeTopics& topics);
  ~DdsInputs();
  DdsInputs(const DdsInputs&) = delete;
  DdsInputs& operator=(const DdsInputs&) = delete;

  // Until a message arrives, wake() is called, or `timeout_ms` passes.
  void wait(double timeout_ms);
  // From any thread: ends the current or the next wait().
  void wake();

  struct Heard {
    std::size_t robot;  // the index in BridgeTopics::robots
    Twist twist;
  };
  // Every twist taken since the last call, oldest first.
  std::vector<Heard> take_twists();
  // Whether a stop for every robot arrived since the last call.
  bool take_stop_every_robot();

  // Samples of the robot's own output (its agent's cmd_vel) skipped on its topic.
  long long skipped_from_agent(std::size_t robot) const { return skipped_from_agent_.at(robot); }
  // The participant, for the bridge's writers (dds_outputs.h).
  std::int32_t participant() const { return participant_; }

 private:
  enum class Writer { Operator, Agent, Unknown };
  void release();
  Writer writer_of(std::int32_t reader, std::uint64_t publication);
  void add_reader(const void* type, const std::string& topic, std::size_t robot);

  std::int32_t participant_ = 0;
  std::int32_t waitset_ = 0;
  std::int32_t guard_ = 0;
  struct Reader {
    std::int32_t reader;
    std::size_t robot;
    bool stamped;
  };
  std::vector<Reader> twist_readers_;
  std::int32_t stop_reader_ = 0;
  std::map<std::uint64_t, Writer> writers_;    // by publication handle, once known
  std::vector<long long> skipped_from_agent_;  // by robot
};

}  // namespace dtmf::ros_bridge
