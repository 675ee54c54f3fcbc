// dtmf-agent: the program on the robot. It listens for command chords, answers each with
// an ACK or NACK chord, drives the robot through cmd_vel and logs every frame it heard.
//
//   dtmf-agent                                   # default microphone and speaker, DDS cmd_vel
//   dtmf-agent --audio wav:x.wav --ack-out wav:y.wav --cmd-vel log --db none   # offline
//   dtmf-agent --stop-robot                      # publish zero on cmd_vel now, and exit
//   dtmf-agent --key link.key --new-key          # once, at pairing: the key's counter state made
// Exit codes: 0 stopped cleanly, 1 a device, the database or DDS could not be had, 2 bad usage.
#include <unistd.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "agent.h"
#include "audio_program.h"
#include "cmd_vel/dds_cmd_vel.h"
#include "cmd_vel/log_cmd_vel.h"
#include "cmd_vel/sim_turtlebot.h"
#include "key_flags.h"
#include "physical/audio_spec.h"
#include "physical/portaudio_device.h"
#include "physical/realtime_priority.h"
#include "stop_guard.h"

namespace {

// Silence played into a new answer stream before listening starts (see reply_player.h).
constexpr std::chrono::milliseconds kAnswerWarmup{1000};

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

struct Flags {
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
  dtmf::program::AudioProgramOptions program;
  dtmf::program::KeyFlags keys;
  int address = 0;
  bool accept_unauthenticated = false;
  bool realtime = false;
  bool stop_robot = false;
  std::optional<int> stop_robot_when_closed;  // the stop guard's pipe (stop_guard.h)
};

dtmf::agent::DdsOptions dds_options(const Flags& f) {
  dtmf::agent::DdsOptions options;
  options.topic = f.topic;
  options.stamped = f.message == "twist_stamped";
  options.domain_id = f.domain_id;
  options.frame_id = f.frame_id;
  return options;
}

// This program's own file, for the stop guard (a second process of the same binary).
std::string own_executable() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find this program's own file for the stop guard: " + error.message());
  return path.string();
}

std::string hostname() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  return name;
}

int run(const Flags& f) {
  using namespace dtmf;
  std::vector<const LinkProfile*> profiles;
  for (const std::string& name : f.profiles) profiles.push_back(&profile_by_name(name));
  if (profiles.empty()) profiles = all_profiles();
  const LinkProfile& profile = *profiles.front();  // all share its sample rate (Agent checks)
  const command::RobotModel& model = command::robot_model_by_name(f.robot);
  const bool offline = physical::is_file_spec(f.audio);

  // Everything that can be missing is checked before the robot could move: the key first,
  // and its counter state, read and locked before the robot listens (a second agent on the
  // same state directory stops here; so does one with no state or damaged state for its key).
  link::LinkOptions link_options = program::robot_link_options(f.keys, static_cast<std::uint8_t>(f.address));
  link_options.accept_unauthenticated = f.accept_unauthenticated;
  if (!link_options.key) {
    spdlog::info(
        "no key: frames are executed unauthenticated, and anyone within earshot can drive this robot "
        "(dtmf-agent --key FILE)");
  } else if (f.accept_unauthenticated) {
    spdlog::warn(
        "--accept-unauthenticated: frames without a MAC are executed too, so anyone within earshot can "
        "drive this robot with the seed profile or an unkeyed fast frame");
  } else {
    spdlog::info("only frames authenticated with key {} are executed; others are refused and logged",
                 link_options.key->id_hex());
  }
  const store::DatabaseUrl db = store::parse_database_flag(f.db);
  if (!store::database_disabled(db)) {
    auto connection = store::connect(db);
    const auto migrated = store::migrate(*connection);
    spdlog::info("database {}: schema version {}", store::describe_database(db), migrated.version_after);
  }
  const std::string ack_out = f.ack_out.empty() ? (offline ? "none" : "default") : f.ack_out;

  std::unique_ptr<agent::ReplyPlayer> replies;
  struct Silent : agent::ReplyPlayer {
    void play(std::vector<float>, double) override {}
    void finish(double) override {}
  };
  if (ack_out == "none")
    replies = std::make_unique<Silent>();
  else if (physical::is_file_spec(ack_out) || offline)
    replies =
        std::make_unique<agent::ReplyTimeline>(profile, physical::open_audio_sink(ack_out, profile.sample_rate_hz));
  else
    // Before the microphone opens: the agent is deaf while its answer stream warms up, and a
    // frame missed then is retransmitted, where an ACK lost then made the seed sender repeat
    // a frame the robot had already executed (reply_player.h).
    replies = std::make_unique<agent::LiveReplyPlayer>(
        [&] {
          const physical::AudioPriorityScope audio_priority;  // the sound library's threads too
          return physical::open_audio_sink(ack_out, profile.sample_rate_hz, f.program.devices);
        }(),
        kAnswerWarmup, /*realtime=*/true);
  spdlog::info("answering through {}", ack_out);

  std::vector<std::unique_ptr<agent::CmdVelOutput>> owned;
  std::unique_ptr<agent::StopGuard> guard;  // with DDS: the wheels stop even if this process is killed
  for (const std::string& name : f.cmd_vel) {
    if (name == "dds") {
      owned.push_back(std::make_unique<agent::DdsCmdVel>(dds_options(f)));
      guard = std::make_unique<agent::StopGuard>(own_executable(), dds_options(f), f.message);
      spdlog::info("cmd_vel: DDS topic {} ({}); stop guard pid {} publishes zero if this process dies", f.topic,
                   f.message, guard->pid());
    } else if (name == "sim") {
      owned.push_back(
          std::make_unique<agent::SimTurtlebot>(model, [](const std::string& line) { spdlog::info("{}", line); }));
    } else if (name == "log") {
      owned.push_back(std::make_unique<agent::LogCmdVel>(stdout));
    }
  }
  std::vector<agent::CmdVelOutput*> outputs;
  for (const auto& o : owned) outputs.push_back(o.get());

  store::StoreOptions store_options;
  store_options.database = db;
  store_options.spill_path = f.spill_file.empty() ? store::default_spill_path("dtmf-agent") : f.spill_file;
  store::Store store(store_options);

  agent::Timeline timeline(!offline);
  agent::AgentOptions options;
  options.profiles = profiles;
  options.link = link_options;
  options.model = model;
  options.publish_rate_hz = f.publish_rate_hz;
  options.continuous_limit_s = f.continuous_limit_s;
  options.host = f.host.empty() ? hostname() : f.host;
  agent::Agent agent(options, *replies, outputs, store, timeline);
  // The microphone last: a live stream opened earlier fills up while the rest starts, and
  // the agent would begin behind real time, hearing the first chords late.
  int min_rate_hz = 0;
  for (const LinkProfile* p : profiles) min_rate_hz = std::max(min_rate_hz, p->min_recording_rate_hz());
  auto source = [&] {
    const physical::AudioPriorityScope audio_priority;  // the sound library's threads too
    return physical::open_audio_source(f.audio, profile.sample_rate_hz, min_rate_hz, f.program.devices);
  }();
  spdlog::info("listening to {}", source->describe());

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::string names;
  for (const LinkProfile* p : profiles) names += (names.empty() ? "" : ", ") + p->name;
  spdlog::info("robot {} ({:.2f} m/s, {:.2f} rad/s), listening with profiles {}, publishing at {:.0f} Hz", model.name,
               model.max_linear_mps, model.max_angular_radps, names, f.publish_rate_hz);
  std::vector<float> block(static_cast<std::size_t>(agent.block_samples()));
  int exit_code = 0;
  const auto started = std::chrono::steady_clock::now();
  timeline.start_now();
  // A recording played back as if it were being heard now.
  const auto pace = [&] {
    if (f.realtime && offline)
      std::this_thread::sleep_until(started + std::chrono::duration<double, std::milli>(agent.audio_ms()));
  };
  if (!offline) {
    // This thread drains the microphone and decodes; starved, it would drop samples.
    std::string how;
    physical::raise_audio_thread_priority(&how);
    spdlog::info("audio threads: {}", how);
  }
  try {
    // Audio that piled up while the agent started is the past: answering it now would put
    // late ACKs on the air, which the sender could take for its next frame's.
    double skipped_ms = 0;
    while (!offline && source->queued_ms() > 1000.0 * static_cast<double>(block.size()) / profile.sample_rate_hz) {
      skipped_ms += 1000.0 * static_cast<double>(source->read(block)) / profile.sample_rate_hz;
    }
    if (skipped_ms > 0) spdlog::info("skipped {:.0f} ms of audio recorded while starting", skipped_ms);
    int behind_warnings = 0;
    while (!g_stop) {
      const std::size_t got = source->read(block);
      if (got == 0) break;
      const double queued_ms = source->queued_ms();
      if (queued_ms > 500 && behind_warnings++ % 100 == 0) {
        spdlog::warn("{:.0f} ms of audio waiting to be decoded: the machine is too busy, answers come late", queued_ms);
      }
      agent.process(std::span<const float>(block.data(), got), queued_ms);
      pace();
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    exit_code = 1;
  }
  if (g_stop)
    agent.stop_now("shutdown signal");
  else if (exit_code == 0)
    agent.finish(pace);
  else
    agent.stop_now("audio input failed");
  replies->finish(agent.audio_ms());
  spdlog::info("{} frames heard in {:.1f} s of audio ({} echoes of frames already taken ignored)", agent.frames_heard(),
               agent.audio_ms() / 1000.0, agent.echoes_ignored());
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("dtmf-agent"));
  Flags f;
  CLI::App app{"dtmf-agent: hears command chords, answers ACK/NACK, drives a TurtleBot3 through cmd_vel"};
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
  app.add_option("--db", f.db,
                 "PostgreSQL URL, or none; default: DTMF_DB_URL, else the libpq environment (PGHOST, ...)")
      ->envname("DTMF_DB_URL");
  app.add_option("--spill-file", f.spill_file, "where log rows wait while the database is away");
  app.add_option("--host", f.host, "name of this robot in the log (default: hostname)");
  dtmf::program::add_key_flags(app, f.keys, "DTMF_AGENT", "/var/lib/dtmf-agent");
  dtmf::program::add_new_key_flag(app, f.keys, "DTMF_AGENT");
  app.add_option("--address", f.address, "this robot's address (0..7): it takes the frames sent to it")
      ->envname("DTMF_AGENT_ADDRESS")
      ->check(CLI::Range(0, 7))
      ->capture_default_str();
  app.add_flag("--accept-unauthenticated", f.accept_unauthenticated,
               "with --key: execute frames without a MAC too (the seed profile's; a warning at start)")
      ->envname("DTMF_AGENT_ACCEPT_UNAUTHENTICATED");
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
    if (f.stop_robot_when_closed) return dtmf::agent::guard_until_closed(*f.stop_robot_when_closed, dds_options(f));
    if (f.stop_robot) return dtmf::agent::stop_robot_now(dds_options(f), std::chrono::seconds(3));
    return run(f);
  });
}
