#include "bridge_setup.h"

#include <spdlog/spdlog.h>

#include <cstdlib>

#include "command/robot_model.h"
#include "ros2/dds_support.h"
#include "server_connection.h"

namespace dtmf::ros_bridge {
namespace {

constexpr const char* kConnection = "The server (as dtmfctl's)";
constexpr const char* kRos = "ROS 2";

// Loopback only: no other machine's cmd_vel reaches the robots through the bridge, and
// nothing the bridge publishes leaves this one. Discovery as ROS 2 Jazzy's own
// ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST sets it for CycloneDDS (no multicast, the
// well-known ports of DDS processes 0-32 on localhost), so that ROS 2 nodes on this machine
// find the bridge: Cyclone ones in that mode, Fast DDS ones (Jazzy's default) in any, as
// they listen on those ports on every interface. No sample over 64 KiB is taken: a cmd_vel is
// under 100 bytes, and a TwistStamped with a huge frame_id must not cost the bridge its
// memory. scripts/lib/quickstart_clients.sh (QUICKSTART_LOOPBACK_DDS) gives its agents the same.
constexpr const char* kLoopbackOnly =
    R"(<General><Interfaces><NetworkInterface name="lo"/></Interfaces><AllowMulticast>false</AllowMulticast></General>)"
    R"(<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>)"
    R"(<Peers><Peer address="localhost"/></Peers></Discovery>)"
    R"(<Internal><MaxSampleSize>65536B</MaxSampleSize></Internal>)";

void choose_dds_network(const BridgeFlags& flags) {
  const char* given = std::getenv("CYCLONEDDS_URI");
  if (given != nullptr && *given != '\0') {
    spdlog::info("DDS: CYCLONEDDS_URI is set, its network is used as given");
  } else if (flags.allow_ros_network) {
    spdlog::warn(
        "DDS: taking cmd_vel from the whole ROS network (--allow-ros-network): anyone who can publish on "
        "domain {} drives the robots by sound, keyed or not",
        ros2::resolve_domain("dtmf-ros-bridge", flags.domain));
  } else {
    ::setenv("CYCLONEDDS_URI", kLoopbackOnly, 1);
  }
}

std::vector<BridgeRobot> robots_of(const cli::ServerChannel& server, const BridgeFlags& flags, double wait_s) {
  auto stub = v1::TeleopService::NewStub(server.channel);
  grpc::ClientContext context;
  if (!server.token.empty()) context.AddMetadata("authorization", "Bearer " + server.token);
  context.AddMetadata("x-dtmf-client", kBridgeClientName);
  context.set_wait_for_ready(true);  // started with the server (systemd, compose): it may come up later
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(static_cast<long>(wait_s * 1000)));
  v1::ListRobotsResponse listed;
  const grpc::Status status = stub->ListRobots(&context, {}, &listed);
  if (!status.ok()) {
    throw std::runtime_error("cannot list dtmf-server's robots at " + flags.server.address + ": \"" +
                             status.error_message().substr(0, 200) +
                             "\" (is it running? --server, --tls-ca and --token-file as for dtmfctl)");
  }
  std::vector<BridgeRobot> robots;
  for (const v1::Robot& r : listed.robots()) {
    const command::RobotModel& model = command::robot_model_by_name(r.model().empty() ? "burger" : r.model());
    robots.push_back({r.name(), {model.max_linear_mps, model.max_angular_radps}});
  }
  return robots;
}

}  // namespace

void add_bridge_flags(CLI::App& app, BridgeFlags& flags) {
  app.add_option("--server", flags.server.address, "dtmf-server address host:port")
      ->envname("DTMF_SERVER")
      ->capture_default_str()
      ->group(kConnection);
  app.add_option("--tls-ca", flags.server.tls_ca, "connect with TLS, trusting this PEM certificate")
      ->envname("DTMF_ROS_BRIDGE_TLS_CA")
      ->group(kConnection);
  app.add_option("--token-file", flags.server.token_file, "the server's bearer token (dtmf-server --auth-token-file)")
      ->envname("DTMF_ROS_BRIDGE_TOKEN_FILE")
      ->group(kConnection);
  app.add_option("--profile", flags.profile, "link profile; it must carry velocity commands (fast)")
      ->envname("DTMF_PROFILE")
      ->capture_default_str()
      ->group(kConnection);
  app.add_option("--lease-s", flags.lease_s, "how long a robot holds a velocity without a renewal (0.3..2)")
      ->envname("DTMF_ROS_BRIDGE_LEASE_S")
      ->check(CLI::Range(0.3, 2.0))
      ->capture_default_str()
      ->group(kConnection);
  app.add_option("--domain", flags.domain, "ROS 2 domain (default: ROS_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, ros2::kMaxDomainId))
      ->group(kRos);
  app.add_option("--timeout-s", flags.timeout_s,
                 "after the last cmd_vel message, the robot is stopped (twist_mux's input timeout)")
      ->envname("DTMF_ROS_BRIDGE_TIMEOUT_S")
      ->check(CLI::Range(0.05, 5.0))
      ->capture_default_str()
      ->group(kRos);
  app.add_flag("--allow-ros-network", flags.allow_ros_network,
               "take cmd_vel from the whole ROS network, not this machine only: anyone on it then drives the robots")
      ->envname("DTMF_ROS_BRIDGE_ALLOW_ROS_NETWORK")
      ->group(kRos);
}

std::unique_ptr<BridgeLoop> start_bridge(const BridgeFlags& flags, double server_wait_s) {
  choose_dds_network(flags);
  const cli::ServerChannel server = cli::open_server_channel(flags.server);
  BridgeSettings settings;
  settings.robots = robots_of(server, flags, server_wait_s);
  settings.domain = ros2::resolve_domain("dtmf-ros-bridge", flags.domain);
  settings.timeout_ms = flags.timeout_s * 1000.0;
  settings.lease_s = flags.lease_s;
  settings.profile = flags.profile;
  settings.token = server.token;
  return std::make_unique<BridgeLoop>(server.channel, std::move(settings));
}

}  // namespace dtmf::ros_bridge
