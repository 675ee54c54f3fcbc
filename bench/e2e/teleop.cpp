// dtmf-bench-teleop: live driving through the whole system, timed at the robot's cmd_vel.
//
// The in-process system of the server tests (tests/server/live_system.h): the server's
// transmitter and the robot's agent in one process, through a simulated room in real time
// (with --rir a measured room both ways, pink noise at -50 dBFS), the gRPC service on a
// loopback port. A Teleop stream is driven as dtmfctl teleop drives it
// (tests/server/teleop_client.h: each new target at once, the current one every 100 ms).
// Three measurements, each at random (seeded) moments:
//   presses  one key of turtlebot3_teleop_key (w/x: ±0.01 m/s, a/d: ±0.1 rad/s; the target
//            kept within ±0.1 m/s and ±1 rad/s): from the new target sent on the stream to
//            the first cmd_vel sample at it, as the frame carries it;
//   kills    a client process (this program with --be-client) driving at 0.1 m/s, 0.5 rad/s
//            killed with SIGKILL: from the kill to the first zero on cmd_vel, and whether
//            the robot moved again;
//   losses   the sender's loudspeaker muted while driving (a lost link: the frame on air
//            cut where it is, every later one unheard, as when the server dies or the
//            laptop closes): from the mute to the first zero on cmd_vel.
// A stop must come within the lease the frames carry + 0.2 s (issue 23).
#include <spawn.h>
#include <sys/wait.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include <spdlog/spdlog.h>

#include "command/command_payload.h"
#include "command/robot_model.h"
#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "live_system.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "teleop_client.h"

extern char** environ;

using namespace dtmf;
using namespace dtmf::bench;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kLinearStep_mps = 0.01;  // turtlebot3_teleop_key's steps
constexpr double kAngularStep_radps = 0.1;
constexpr double kLinearSpan_mps = 0.1;  // the presses keep the target within these
constexpr double kAngularSpan_radps = 1.0;
constexpr double kStopMargin_ms = 200;  // the bound: the lease + this
constexpr auto kPressTimeout = 3s;      // a press not on cmd_vel by then counts as missed
constexpr double kDriveLinear_mps = 0.1, kDriveAngular_radps = 0.5;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

bool moving(const agent::Velocity& v) { return v != agent::Velocity{}; }

// The velocity the robot executes for a target: through the frame's fields.
agent::Velocity as_carried(const command::RobotModel& model, double linear, double angular, double lease_s) {
  const auto carried = std::get<command::Velocity>(
      command::quantised_payload(command::velocity_command(model, linear, angular, lease_s)));
  return {command::linear_mps(model, carried), command::angular_radps(model, carried)};
}

double carried_lease_s(const command::RobotModel& model, double lease_s) {
  return std::get<command::Velocity>(command::quantised_payload(command::velocity_command(model, 0, 0, lease_s)))
      .lease_s;
}

// Until the newest cmd_vel sample at or after `since` satisfies `wanted`: its time, or
// nothing once `within` has passed.
template <typename Predicate>
std::optional<Clock::time_point> wait_for_cmd_vel(test_support::LiveSystem& system, Clock::time_point since,
                                                  Predicate wanted, std::chrono::milliseconds within) {
  // Only the samples not yet seen are fetched: the agent publishes every 10 ms or so, and
  // copying the whole history each time would steal the real-time system's CPU.
  std::size_t seen = 0;
  for (const auto deadline = Clock::now() + within; Clock::now() < deadline; std::this_thread::sleep_for(2ms)) {
    const auto fresh = system.velocities(seen);
    seen += fresh.size();
    for (const auto& s : fresh) {
      if (s.at >= since && wanted(s.velocity)) return s.at;
    }
  }
  return std::nullopt;
}

struct StopTrial {
  double stop_ms = -1;       // the cut → the first zero; -1: never stopped
  bool moved_after = false;  // non-zero again after that zero
};

// After the cut at `cut`: when the robot first published zero, and whether it moved again
// in the `settle` that follows.
StopTrial stop_after(test_support::LiveSystem& system, Clock::time_point cut, std::chrono::milliseconds settle) {
  std::this_thread::sleep_for(settle);
  StopTrial trial;
  bool stopped = false;
  for (const auto& s : system.velocities()) {
    if (s.at < cut) continue;
    if (!stopped && !moving(s.velocity)) {
      stopped = true;
      trial.stop_ms = ms_between(cut, s.at);
    } else if (stopped && moving(s.velocity)) {
      trial.moved_after = true;
    }
  }
  return trial;
}

nlohmann::json summary(const std::vector<double>& ms) {
  return {{"median", percentile(ms, 0.5)}, {"p95", percentile(ms, 0.95)}, {"max", percentile(ms, 1.0)}, {"all", ms}};
}

// The stops of one kind of trial ("kill", "loss"), printed as they come.
struct StopTrials {
  explicit StopTrials(std::string kind) : name(std::move(kind)) {}
  std::string name;
  std::vector<double> stop_ms;
  int not_stopped = 0, moved_after = 0;

  void add(const StopTrial& t, int index, int count, const char* after) {
    if (t.stop_ms < 0)
      ++not_stopped;
    else
      stop_ms.push_back(t.stop_ms);
    moved_after += t.moved_after;
    std::printf("%s %2d/%d: stopped %.0f ms after %s%s\n", name.c_str(), index + 1, count, t.stop_ms, after,
                t.moved_after ? ", then MOVED again" : "");
    std::fflush(stdout);
  }
  // Its fields of the JSON: KINDs, KINDs_not_stopped, KINDs_moved_after, KIND_to_stop_ms.
  void write(nlohmann::json& doc, const std::string& plural, int count) const {
    doc[plural] = count;
    doc[plural + "_not_stopped"] = not_stopped;
    doc[plural + "_moved_after"] = moved_after;
    doc[name + "_to_stop_ms"] = summary(stop_ms);
  }
};

// --be-client: a Teleop client driving until it is killed.
int be_client(int port, double lease_s, const std::string& profile) {
  auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials());
  auto stub = v1::TeleopService::NewStub(channel);
  test_support::TeleopClient client(*stub, kDriveLinear_mps, kDriveAngular_radps, lease_s, profile);
  for (;;) std::this_thread::sleep_for(1s);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-teleop: live driving, key press to cmd_vel and stops, through the whole system");
  std::string profile_name = "fast", json_path, rir_file;
  int presses = 100, kills = 10, losses = 10, client_port = 0;
  double lease_s = 1.0, air_block_ms = 5;
  std::uint64_t seed = 1;
  bool authenticated = false;
  app.add_option("--profile", profile_name, "link profile: one that carries velocity commands")->capture_default_str();
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--presses", presses, "key presses to time")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--kills", kills, "client processes to kill with -9")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--losses", losses, "times to cut the link")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--lease-s", lease_s, "the stream's lease")->capture_default_str()->check(CLI::Range(0.3, 2.0));
  app.add_option("--rir", rir_file, "a measured room both ways (its impulse response file), pink noise at -50 dBFS");
  app.add_option("--air-block-ms", air_block_ms, "the simulated room's audio period (5 ms: a low-latency device)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 50.0));
  app.add_option("--seed", seed, "random seed (keys and moments)")->capture_default_str();
  app.add_option("--be-client", client_port, "internal: be the client that --kills kills, on this port");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  if (client_port > 0) return be_client(client_port, lease_s, profile_name);
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        const command::RobotModel& model = command::burger();
        spdlog::set_level(spdlog::level::warn);  // the per-frame lines would drown the summary
        test_support::LiveSystemOptions options;
        options.profile = &profile;
        options.air_block_ms = air_block_ms;
        options.rir_file = rir_file;
        options.sender_key = options.robot_key = bench_key(authenticated);
        test_support::LiveSystem system(options);
        spdlog::set_level(spdlog::level::warn);
        auto stub = system.client();
        std::mt19937_64 rng(seed);
        const auto pause = [&](double lo_s, double hi_s) {
          std::this_thread::sleep_for(std::chrono::duration<double>(std::uniform_real_distribution(lo_s, hi_s)(rng)));
        };
        const double lease_carried_s = carried_lease_s(model, lease_s);
        const double bound_ms = 1000 * lease_carried_s + kStopMargin_ms;
        const auto settle = std::chrono::milliseconds(static_cast<int>(bound_ms) + 800);
        bool complete = true;

        // Presses.
        std::vector<double> press_ms;
        int presses_missed = 0;
        {
          test_support::TeleopClient client(*stub, 0, 0, lease_s, profile.name);
          double linear = 0, angular = 0;
          for (int i = 0; i < presses; ++i) {
            pause(0.2, 0.8);
            const char key = "wxad"[rng() % 4];
            const double sign = (key == 'w' || key == 'a') ? 1 : -1;
            double& part = (key == 'w' || key == 'x') ? linear : angular;
            const double step = (key == 'w' || key == 'x') ? kLinearStep_mps : kAngularStep_radps;
            const double span = (key == 'w' || key == 'x') ? kLinearSpan_mps : kAngularSpan_radps;
            part = std::round((part + (std::abs(part + sign * step) > span + 1e-9 ? -sign : sign) * step) * 100) / 100;
            const agent::Velocity wanted = as_carried(model, linear, angular, lease_s);
            const auto sent = Clock::now();
            client.target(linear, angular);
            const auto reached = wait_for_cmd_vel(
                system, sent,
                [&](const agent::Velocity& v) {
                  return std::abs(v.linear_mps - wanted.linear_mps) < 1e-6 &&
                         std::abs(v.angular_radps - wanted.angular_radps) < 1e-6;
                },
                kPressTimeout);
            if (reached) {
              press_ms.push_back(ms_between(sent, *reached));
            } else {
              ++presses_missed;
            }
            std::printf("press %3d/%d  %c -> %+.2f m/s %+.1f rad/s: %s\n", i + 1, presses, key, linear, angular,
                        reached ? (std::to_string(static_cast<int>(press_ms.back())) + " ms").c_str() : "NOT reached");
            std::fflush(stdout);
          }
          client.close();
        }
        std::this_thread::sleep_for(settle);

        // Kills: a client in a process of its own, killed with -9.
        StopTrials killed_trials{"kill"};
        for (int i = 0; i < kills; ++i) {
          const std::string port = std::to_string(system.port()), lease = std::to_string(lease_s);
          std::vector<std::string> args = {argv[0], "--be-client", port, "--lease-s", lease, "--profile", profile.name};
          std::vector<char*> argp;
          for (auto& a : args) argp.push_back(a.data());
          argp.push_back(nullptr);
          pid_t child = 0;
          if (posix_spawn(&child, argv[0], nullptr, nullptr, argp.data(), environ) != 0) {
            throw std::runtime_error("cannot start a client process (" + std::string(argv[0]) + ")");
          }
          const bool drove = wait_for_cmd_vel(system, Clock::now(), moving, 10s).has_value();
          pause(0.3, 1.5);
          const auto killed = Clock::now();
          ::kill(child, SIGKILL);
          ::waitpid(child, nullptr, 0);
          if (!drove) {
            std::printf("kill %2d/%d: the client never drove the robot\n", i + 1, kills);
            complete = false;
            continue;
          }
          killed_trials.add(stop_after(system, killed, settle), i, kills, "the kill");
        }

        // Losses: the link cut in the middle of driving.
        StopTrials lost_trials{"loss"};
        {
          test_support::TeleopClient client(*stub, kDriveLinear_mps, kDriveAngular_radps, lease_s, profile.name);
          for (int i = 0; i < losses; ++i) {
            if (!wait_for_cmd_vel(system, Clock::now(), moving, 10s)) {
              std::printf("loss %2d/%d: the robot never drove\n", i + 1, losses);
              complete = false;
              break;
            }
            pause(0.3, 1.5);
            const auto cut = Clock::now();
            system.mute_sender(true);
            const StopTrial t = stop_after(system, cut, settle);
            system.mute_sender(false);
            lost_trials.add(t, i, losses, "the link was cut");
          }
          client.close();
        }

        const std::vector<double>& kill_ms = killed_trials.stop_ms;
        const std::vector<double>& loss_ms = lost_trials.stop_ms;
        std::printf(
            "teleop %s%s: key press -> cmd_vel median %.0f ms, p95 %.0f ms, max %.0f ms (%d of %d not reached in "
            "%lld s); stop after a kill -9: max %.0f ms of %zu; after a lost link: max %.0f ms of %zu (bound: lease "
            "%.2f s + 0.2 s = %.0f ms)\n",
            profile.name.c_str(), authenticated ? "+key" : "", percentile(press_ms, 0.5), percentile(press_ms, 0.95),
            percentile(press_ms, 1.0), presses_missed, presses,
            static_cast<long long>(std::chrono::duration_cast<std::chrono::seconds>(kPressTimeout).count()),
            percentile(kill_ms, 1.0), kill_ms.size(), percentile(loss_ms, 1.0), loss_ms.size(), lease_carried_s,
            bound_ms);
        nlohmann::json doc = {{"benchmark", "teleop"},
                              {"profile", profile.name},
                              {"authenticated", authenticated},
                              {"seed", seed},
                              {"rir", rir_file},
                              {"lease_s", lease_s},
                              {"carried_lease_s", lease_carried_s},
                              {"stop_bound_ms", bound_ms},
                              {"presses", presses},
                              {"presses_not_reached", presses_missed},
                              {"press_to_cmd_vel_ms", summary(press_ms)}};
        killed_trials.write(doc, "kills", kills);
        lost_trials.write(doc, "losses", losses);
        write_json(json_path, doc);
        return complete ? 0 : 1;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-teleop: %s\n", why.c_str()); });
}
