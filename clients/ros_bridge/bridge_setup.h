// dtmf-ros-bridge's flags and its start: the DDS network it listens on, the channel to
// dtmf-server, and the robots it drives (ListRobots, each with its model's limits).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>

#include "bridge_loop.h"
#include "global_options.h"

namespace dtmf::ros_bridge {

struct BridgeFlags {
  cli::ServerOptions server;       // --server, --tls-ca, --token-file: as dtmfctl's
  std::optional<int> domain;       // --domain; else ROS_DOMAIN_ID, else 0
  double timeout_s = 0.5;          // --timeout-s: twist_mux's input timeout
  double lease_s = 1.0;            // --lease-s
  std::string profile = "fast";    // --profile
  bool allow_ros_network = false;  // --allow-ros-network
};

void add_bridge_flags(CLI::App& app, BridgeFlags& flags);

// The loop CycloneDDS's configuration is read for: loopback only unless the user set
// CYCLONEDDS_URI or allowed the ROS network. Then the server's robots (waiting for the
// server up to `server_wait_s`). Throws std::invalid_argument for a bad flag, std::runtime_error
// (naming what to do) when the server cannot be had, ros2::DdsError when DDS cannot start.
std::unique_ptr<BridgeLoop> start_bridge(const BridgeFlags& flags, double server_wait_s = 30);

}  // namespace dtmf::ros_bridge
