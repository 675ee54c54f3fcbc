#include "agent_program.h"

#include <unistd.h>

#include <spdlog/spdlog.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <thread>

#include "agent.h"
#include "cmd_vel/log_cmd_vel.h"
#include "cmd_vel/sim_turtlebot.h"
#include "physical/audio_spec.h"
#include "physical/portaudio_device.h"
#include "physical/realtime_priority.h"
#include "stop_guard.h"

namespace dtmf::agent {

namespace {

// Silence played into a new answer stream before listening starts (see reply_player.h).
constexpr std::chrono::milliseconds kAnswerWarmup{1000};

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

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

// The key and its counter state, read and locked before the robot listens (a second agent on
// the same state directory stops here; so does one with no state or damaged state for its
// key), and a line that says who may drive.
link::LinkOptions announced_link_options(const AgentFlags& f) {
  link::LinkOptions options = program::robot_link_options(f.keys, static_cast<std::uint8_t>(f.address));
  options.accept_unauthenticated = f.accept_unauthenticated;
  if (!options.key) {
    spdlog::info(
        "no key: frames are executed unauthenticated, and anyone within earshot can drive this robot "
        "(dtmf-agent --key FILE)");
  } else if (f.accept_unauthenticated) {
    spdlog::warn(
        "--accept-unauthenticated: frames without a MAC are executed too, so anyone within earshot can "
        "drive this robot with the seed profile or an unkeyed fast frame");
  } else {
    spdlog::info("only frames authenticated with key {} are executed; others are refused and logged",
                 options.key->id_hex());
  }
  return options;
}

std::unique_ptr<ReplyPlayer> open_answers(const AgentFlags& f, const LinkProfile& profile, bool offline) {
  const std::string ack_out = f.ack_out.empty() ? (offline ? "none" : "default") : f.ack_out;
  struct Silent : ReplyPlayer {
    void play(std::vector<float>, double) override {}
    void finish(double) override {}
  };
  std::unique_ptr<ReplyPlayer> replies;
  if (ack_out == "none") {
    replies = std::make_unique<Silent>();
  } else if (physical::is_file_spec(ack_out) || offline) {
    replies = std::make_unique<ReplyTimeline>(profile, physical::open_audio_sink(ack_out, profile.sample_rate_hz));
  } else {
    // Before the microphone opens: the agent is deaf while its answer stream warms up, and a
    // frame missed then is retransmitted, where an ACK lost then made the seed sender repeat
    // a frame the robot had already executed (reply_player.h).
    replies = std::make_unique<LiveReplyPlayer>(
        [&] {
          const physical::AudioPriorityScope audio_priority;  // the sound library's threads too
          return physical::open_audio_sink(ack_out, profile.sample_rate_hz, f.program.devices);
        }(),
        kAnswerWarmup, /*realtime=*/true);
  }
  spdlog::info("answering through {}", ack_out);
  return replies;
}

struct CmdVelOutputs {
  std::vector<std::unique_ptr<CmdVelOutput>> owned;
  std::unique_ptr<StopGuard> guard;  // with DDS: the wheels stop even if this process is killed
  std::vector<CmdVelOutput*> outputs() const {
    std::vector<CmdVelOutput*> all;
    for (const auto& o : owned) all.push_back(o.get());
    return all;
  }
};

CmdVelOutputs open_cmd_vel(const AgentFlags& f, const command::RobotModel& model) {
  CmdVelOutputs out;
  for (const std::string& name : f.cmd_vel) {
    if (name == "dds") {
      out.owned.push_back(std::make_unique<DdsCmdVel>(dds_options(f)));
      out.guard = std::make_unique<StopGuard>(own_executable(), dds_options(f), f.message);
      spdlog::info("cmd_vel: DDS topic {} ({}); stop guard pid {} publishes zero if this process dies", f.topic,
                   f.message, out.guard->pid());
    } else if (name == "sim") {
      out.owned.push_back(
          std::make_unique<SimTurtlebot>(model, [](const std::string& line) { spdlog::info("{}", line); }));
    } else if (name == "log") {
      out.owned.push_back(std::make_unique<LogCmdVel>(stdout));
    }
  }
  return out;
}

// Reads and decodes until a signal, the end of the input or a failed device; the exit code.
// `pace` runs after each block (a recording played as if heard now).
int listen(Agent& agent, physical::AudioSource& source, bool offline, const std::function<void()>& pace) {
  std::vector<float> block(static_cast<std::size_t>(agent.block_samples()));
  const double block_ms = 1000.0 * static_cast<double>(block.size()) / source.sample_rate_hz();
  try {
    // Audio that piled up while the agent started is the past: answering it now would put
    // late ACKs on the air, which the sender could take for its next frame's.
    double skipped_ms = 0;
    while (!offline && source.queued_ms() > block_ms) {
      skipped_ms += 1000.0 * static_cast<double>(source.read(block)) / source.sample_rate_hz();
    }
    if (skipped_ms > 0) spdlog::info("skipped {:.0f} ms of audio recorded while starting", skipped_ms);
    int behind_warnings = 0;
    while (!g_stop) {
      const std::size_t got = source.read(block);
      if (got == 0) break;
      const double queued_ms = source.queued_ms();
      if (queued_ms > 500 && behind_warnings++ % 100 == 0) {
        spdlog::warn("{:.0f} ms of audio waiting to be decoded: the machine is too busy, answers come late", queued_ms);
      }
      agent.process(std::span<const float>(block.data(), got), queued_ms);
      pace();
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

DdsOptions dds_options(const AgentFlags& f) {
  DdsOptions options;
  options.topic = f.topic;
  options.stamped = f.message == "twist_stamped";
  options.domain_id = f.domain_id;
  options.frame_id = f.frame_id;
  return options;
}

int run_agent(const AgentFlags& f) {
  std::vector<const LinkProfile*> profiles;
  for (const std::string& name : f.profiles) profiles.push_back(&profile_by_name(name));
  if (profiles.empty()) profiles = all_profiles();
  const LinkProfile& profile = *profiles.front();  // all share its sample rate (Agent checks)
  const command::RobotModel& model = command::robot_model_by_name(f.robot);
  const bool offline = physical::is_file_spec(f.audio);

  // Everything that can be missing is checked before the robot could move: the key first.
  const link::LinkOptions link_options = announced_link_options(f);
  const store::DatabaseUrl db = store::parse_database_flag(f.db);
  if (!store::database_disabled(db)) {
    auto connection = store::connect(db);
    const auto migrated = store::migrate(*connection);
    spdlog::info("database {}: schema version {}", store::describe_database(db), migrated.version_after);
  }
  const std::unique_ptr<ReplyPlayer> replies = open_answers(f, profile, offline);
  const CmdVelOutputs cmd_vel = open_cmd_vel(f, model);

  store::StoreOptions store_options;
  store_options.database = db;
  store_options.spill_path = f.spill_file.empty() ? store::default_spill_path("dtmf-agent") : f.spill_file;
  store::Store store(store_options);

  Timeline timeline(!offline);
  AgentOptions options;
  options.profiles = profiles;
  options.link = link_options;
  options.model = model;
  options.publish_rate_hz = f.publish_rate_hz;
  options.continuous_limit_s = f.continuous_limit_s;
  options.host = f.host.empty() ? hostname() : f.host;
  Agent agent(options, *replies, cmd_vel.outputs(), store, timeline);
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
  const auto started = std::chrono::steady_clock::now();
  timeline.start_now();
  const auto pace = [&] {
    if (f.realtime && offline)
      std::this_thread::sleep_until(started + std::chrono::duration<double, std::milli>(agent.audio_ms()));
  };
  // This thread decodes at normal priority: a device is drained by a thread of its own
  // (physical/capture_thread.h), which only copies.
  const int exit_code = listen(agent, *source, offline, pace);
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

}  // namespace dtmf::agent
