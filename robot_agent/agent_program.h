// dtmf-agent's program: its flags, and the robot put together from them in the order it
// needs — the key and its counter state, the database, the answer player, the cmd_vel
// outputs (with DDS, the stop guard), the agent, the microphone last — then the listening
// loop until a signal, the end of a recording or a failed device.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "audio_program.h"
#include "cmd_vel/dds_cmd_vel.h"
#include "key_flags.h"

namespace dtmf::agent {

struct AgentFlags {
  std::string audio = "default";
  std::string ack_out;  // default: "none" for a file input, else the default device
  std::vector<std::string> cmd_vel{"dds"};
  std::vector<std::string> profiles;  // empty: every profile
  std::string robot = "burger";
  double publish_rate_hz = 20;
  double continuous_limit_s = 30;
  std::string topic = "cmd_vel";
  std::string message = "twist_stamped";
  std::optional<int> domain_id;
  std::string frame_id;
  std::optional<std::string> db;
  std::string spill_file;
  std::string host;
  program::AudioProgramOptions program;
  program::KeyFlags keys;
  int address = 0;
  bool accept_unauthenticated = false;
  bool realtime = false;
  bool stop_robot = false;
  std::optional<int> stop_robot_when_closed;  // the stop guard's pipe (stop_guard.h)
};

// The DDS outputs' settings from the flags (also for --stop-robot and the stop guard).
DdsOptions dds_options(const AgentFlags& f);

// Runs the agent until SIGINT/SIGTERM or the end of its input; the exit code.
int run_agent(const AgentFlags& f);

}  // namespace dtmf::agent
