// dtmf-agent: the program on the robot. It listens for command chords, answers each with
// an ACK or NACK chord, drives the robot through cmd_vel and logs every frame it heard.
//
//   dtmf-agent                                   # default microphone and speaker, DDS cmd_vel
//   dtmf-agent --audio wav:x.wav --ack-out wav:y.wav --cmd-vel log --db none   # offline
//   dtmf-agent --stop-robot                      # publish zero on cmd_vel now, and exit
//   dtmf-agent --key link.key --new-key          # once, at pairing: the key's counter state made
// Exit codes: 0 stopped cleanly, 1 a device, the database or DDS could not be had, 2 bad usage.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <chrono>

#include "agent_program.h"
#include "stop_guard.h"

namespace {

// What it hears and answers with, and how it drives the robot.
void add_driving_flags(CLI::App& app, dtmf::agent::AgentFlags& f) {
  app.add_option("--audio", f.audio, "where to listen: wav:FILE, a device name or index, or default")
      ->envname("DTMF_AGENT_AUDIO")
      ->capture_default_str();
  app.add_option("--ack-out", f.ack_out,
                 "where to answer: wav:FILE, a device, default, or none (default: none for wav: input, else default)")
      ->envname("DTMF_AGENT_ACK_OUT");
  app.add_option("--cmd-vel", f.cmd_vel,
                 "outputs, one or more of: dds (ROS 2), sim (simulated robot), log (JSON lines on stdout)")
      ->delimiter(',')
      ->check(CLI::IsMember({"dds", "sim", "log"}))
      ->envname("DTMF_AGENT_CMD_VEL")
      ->capture_default_str();
  app.add_option("--profile", f.profiles,
                 "link profiles to listen with, comma-separated (default: all of " + dtmf::profile_names() + ")")
      ->delimiter(',');
  app.add_option("--robot", f.robot, "TurtleBot3 model: burger or waffle")
      ->envname("TURTLEBOT3_MODEL")
      ->check(CLI::IsMember({"burger", "waffle", "waffle_pi"}))
      ->capture_default_str();
  app.add_option("--publish-rate-hz", f.publish_rate_hz, "cmd_vel publish rate")
      ->check(CLI::Range(1.0, 200.0))
      ->capture_default_str();
  app.add_option("--continuous-limit-s", f.continuous_limit_s, "stop a DRIVE_FORWARD / TURN after this long, 0 = never")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  app.add_option("--topic", f.topic, "ROS 2 topic")->envname("DTMF_AGENT_TOPIC")->capture_default_str();
  app.add_option("--message", f.message, "twist_stamped (ROS 2 Jazzy) or twist (Humble)")
      ->check(CLI::IsMember({"twist_stamped", "twist"}))
      ->envname("DTMF_AGENT_MESSAGE")
      ->capture_default_str();
  app.add_option("--ros-domain-id", f.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  app.add_option("--frame-id", f.frame_id, "header.frame_id of TwistStamped");
}

// Where it logs, its keys and its address.
void add_record_and_key_flags(CLI::App& app, dtmf::agent::AgentFlags& f) {
  app.add_option("--db", f.db,
                 "PostgreSQL URL, or none; default: DTMF_DB_URL, else the libpq environment (PGHOST, ...)")
      ->envname("DTMF_DB_URL");
  app.add_option("--spill-file", f.spill_file, "where log rows wait while the database is away");
  app.add_option("--host", f.host, "name of this robot in the log (default: hostname)");
  dtmf::program::add_key_flags(app, f.keys, "DTMF_AGENT", "/var/lib/dtmf-agent");
  dtmf::program::add_new_key_flag(app, f.keys, "DTMF_AGENT");
  dtmf::program::add_room_key_flag(app, f.keys, "DTMF_AGENT");
  app.add_option("--address", f.address, "this robot's address (0..7): it takes the frames sent to it")
      ->envname("DTMF_AGENT_ADDRESS")
      ->check(CLI::Range(0, 7))
      ->capture_default_str();
  app.add_flag("--accept-unauthenticated", f.accept_unauthenticated,
               "with --key: execute frames without a MAC too (the seed profile's; a warning at start)")
      ->envname("DTMF_AGENT_ACCEPT_UNAUTHENTICATED");
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("dtmf-agent"));
  dtmf::agent::AgentFlags f;
  CLI::App app{"dtmf-agent: hears command chords, answers ACK/NACK, drives a TurtleBot3 through cmd_vel"};
  add_driving_flags(app, f);
  add_record_and_key_flags(app, f);
  dtmf::program::add_audio_program_options(app, f.program);
  f.program.without_devices =
      "or run on recordings: --audio wav:FILE --ack-out wav:FILE (scripts/air start gives a "
      "private PulseAudio)";
  app.add_flag("--realtime", f.realtime, "with wav: input, take as long as the recording lasts (as if heard live)");
  app.add_flag("--stop-robot", f.stop_robot,
               "publish zero on cmd_vel (DDS: --topic, --message, --ros-domain-id) and exit: stops the robot now");
  app.add_option("--stop-robot-when-closed", f.stop_robot_when_closed,
                 "(internal) the stop guard: publish zero on cmd_vel once this descriptor reads end-of-file")
      ->group("");
  app.footer(
      "Exit codes: 0 stopped cleanly, 1 a device, the database or DDS could not be had, 2 bad usage.\n"
      "Safety: zero velocity is published when a duration ends, on STOP, on SIGINT/SIGTERM, at the\n"
      "end of a recording, and when continuous motion exceeds --continuous-limit-s; with DDS, a stop\n"
      "guard process publishes it too if the agent dies, even by SIGKILL.");
  return dtmf::program::audio_program_main(app, argc, argv, f.program, [&] {
    if (f.stop_robot_when_closed)
      return dtmf::agent::guard_until_closed(*f.stop_robot_when_closed, dtmf::agent::dds_options(f));
    if (f.stop_robot) return dtmf::agent::stop_robot_now(dtmf::agent::dds_options(f), std::chrono::seconds(3));
    return dtmf::agent::run_agent(f);
  });
}
