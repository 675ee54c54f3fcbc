// dtmf-ros-bridge: ROS 2's cmd_vel in, the link's health out (docs/ros.md). teleop_twist_keyboard,
// teleop_twist_joy or Nav2 publish cmd_vel on this machine; the bridge drives the robots by
// sound through dtmf-server's Teleop stream and publishes /diagnostics.
//
//   dtmf-ros-bridge [--server localhost:50051] [--domain N] [--timeout-s 0.5]
//
// SIGINT or SIGTERM brings every robot it drives to a stop, then ends it.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>
#include <thread>

#include "bridge_setup.h"
#include "program_main.h"

namespace {

std::string topic_list(const dtmf::ros_bridge::BridgeTopics& topics) {
  std::string list;
  for (const auto& r : topics.robots)
    list += "/" + r.cmd_vel + " (" + (r.robot.empty() ? "the robot" : r.robot) + "), ";
  return list + "/" + topics.stop_every_robot + ", /" + topics.diagnostics;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dtmf;
  CLI::App app("dtmf-ros-bridge: drive dtmf-teleop's robots from ROS 2's cmd_vel; their link's health on /diagnostics");
  ros_bridge::BridgeFlags flags;
  ros_bridge::add_bridge_flags(app, flags);
  if (const auto done = program::parse(app, argc, argv)) return *done;
  return program::run(
      [&] {
        // The ending signals are taken by sigwait, so every thread started from here on
        // (DDS's, gRPC's) inherits them blocked.
        sigset_t ending;
        sigemptyset(&ending);
        sigaddset(&ending, SIGINT);
        sigaddset(&ending, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &ending, nullptr);
        const auto bridge = ros_bridge::start_bridge(flags);
        std::thread signals([&] {
          int signal = 0;
          sigwait(&ending, &signal);
          spdlog::info("stopping every robot driven, then leaving ({})", signal == SIGINT ? "SIGINT" : "SIGTERM");
          bridge->stop();
        });
        signals.detach();  // it outlives run() only when run() failed, and the process then ends
        std::cout << "ros bridge on domain " << bridge->domain() << ": " << topic_list(bridge->topics()) << std::endl;
        bridge->run();
        return program::kExitOk;
      },
      [](const std::string& why) { spdlog::error("dtmf-ros-bridge: {}", why); });
}
