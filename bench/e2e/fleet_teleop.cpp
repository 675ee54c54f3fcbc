// dtmf-bench-fleet-teleop: three robots driven live at once from one sender, timed at each
// robot's cmd_vel: the Fleet section's Teleop targets of docs/benchmarks.md (issue 37).
//
// The in-process fleet of the server tests (tests/server/fleet_system.h): one transmitter
// driving robot1..robot3 (addresses 1..3, 1, 2 and 3 m from the loudspeaker) through the
// seminar room both ways (measured, pink noise at -50 dBFS), three agents in the same room,
// each with its own key (and the room key), in real time; one Teleop stream per robot, each
// driven as dtmfctl teleop drives it (tests/server/teleop_client.h). Each robot's targets keep
// to a range of linear speeds no other robot's reach (robot k: 0.02 + 0.06 (k - 1) m/s and up
// to 0.04 more), so a velocity a robot executes outside its range is another robot's frame.
// For `--seconds`, a key press every `--press-every-s` on average (exponential gaps), each on
// a robot taken in turn: ±0.01 m/s within its range. Measured per robot:
//   renewals  velocities it executed per second (each a renewal of its lease): VELOCITY frames
//             of its stream, and (keyed) joint renewals, counted also apart;
//   presses   from the new target sent on its stream to the first cmd_vel sample at it;
//   lapses    standstills on cmd_vel while its operator held a non-zero target (a lease ran out);
//   wrong     velocities it executed outside its range (another robot's frames).
// And the sender's air: blocks of another's sound it heard, and frames it deferred for them
// (a lapse of every robot at once with none was a stalled process, not a wait for the air).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "command/command_payload.h"
#include "command/robot_model.h"
#include "common/bench_report.h"
#include "fleet_system.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "teleop_client.h"

using namespace dtmf;
using namespace dtmf::bench;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

constexpr std::size_t kRobots = 3;
constexpr double kStep_mps = 0.01;        // turtlebot3_teleop_key's
constexpr double kRangeStart_mps = 0.02;  // robot k's range: start + spacing (k - 1), span wide
constexpr double kRangeSpacing_mps = 0.06;
constexpr double kRangeSpan_mps = 0.04;
constexpr double kAngular_radps = 0.3;
constexpr auto kPressTimeout = 3s;

double range_low(std::size_t k) { return kRangeStart_mps + kRangeSpacing_mps * static_cast<double>(k); }

// The linear speed a robot executes for a target: through the frame's fields.
double as_carried(const command::RobotModel& model, double linear, double lease_s) {
  const auto carried = std::get<command::Velocity>(
      command::quantised_payload(command::velocity_command(model, linear, kAngular_radps, lease_s)));
  return command::linear_mps(model, carried);
}

struct RobotFigures {
  std::vector<double> press_ms;
  int presses = 0, missed = 0, lapses = 0, wrong = 0, renewals = 0, joint = 0;
};

nlohmann::json summary(const std::vector<double>& ms) {
  return {{"median", percentile(ms, 0.5)},
          {"p95", percentile(ms, 0.95)},
          {"max", percentile(ms, 1.0)},
          {"count", ms.size()}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dtmf-bench-fleet-teleop: three robots driven live at once from one sender, through the seminar room"};
  std::string json_path, rir = "bench/rirs/seminar_room_clap.wav";
  double seconds = 60, press_every_s = 1.0, lease_s = 1.0;
  bool authenticated = false;
  std::uint64_t seed = 1;
  app.add_option("--seconds", seconds, "how long the three streams drive")
      ->check(CLI::Range(5.0, 3600.0))
      ->capture_default_str();
  app.add_option("--press-every-s", press_every_s, "a key press this often on average, robots in turn")
      ->check(CLI::Range(0.2, 60.0))
      ->capture_default_str();
  app.add_option("--lease-s", lease_s, "each stream's lease")->check(CLI::Range(0.3, 2.0))->capture_default_str();
  app.add_flag("--authenticated", authenticated, "each robot its own key, and the room key (as in a real fleet)");
  app.add_option("--rir", rir, "the measured room both ways")->capture_default_str();
  app.add_option("--seed", seed, "the presses' moments and keys")->capture_default_str();
  app.add_option("--json", json_path, "also write the results as JSON");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        test_support::FleetOptions options;
        options.names = {"robot1", "robot2", "robot3"};
        options.positions_m = {1.0, 2.0, 3.0};
        options.keys = authenticated ? test_support::FleetKeys::OwnAndRoom : test_support::FleetKeys::None;
        options.rir_file = rir;
        test_support::FleetSystem fleet(options);
        std::array<double, kRobots> target{};
        std::vector<std::unique_ptr<test_support::TeleopClient>> clients;
        for (std::size_t k = 0; k < kRobots; ++k) {
          target[k] = range_low(k) + kRangeSpan_mps / 2;
          clients.push_back(std::make_unique<test_support::TeleopClient>(fleet.stub(), target[k], kAngular_radps,
                                                                         lease_s, "fast", fleet.name(k)));
        }
        for (std::size_t k = 0; k < kRobots; ++k) {
          if (!clients[k]->confirmed(target[k], kAngular_radps, 20s))
            throw std::runtime_error(fleet.name(k) + "'s stream drove nothing within 20 s");
        }
        const command::RobotModel& burger = command::burger();
        const command::RobotModel& waffle = command::waffle();  // robot 2's model (fleet_system.h)
        const auto model_of = [&](std::size_t k) -> const command::RobotModel& { return k == 1 ? waffle : burger; };
        std::array<RobotFigures, kRobots> figures;
        std::array<std::size_t, kRobots> executed_before{};
        std::array<int, kRobots> joint_before{};
        for (std::size_t k = 0; k < kRobots; ++k) {
          executed_before[k] = fleet.robot(k).executed().size();
          joint_before[k] = fleet.robot(k).renewals();
        }
        std::array<std::size_t, kRobots> seen{};
        for (std::size_t k = 0; k < kRobots; ++k) seen[k] = fleet.robot(k).samples().size();
        std::mt19937_64 rng(seed);
        std::exponential_distribution<double> gap(1.0 / press_every_s);
        const auto started = Clock::now();
        const auto end = started + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
        std::size_t next = 0;
        while (Clock::now() < end) {
          std::this_thread::sleep_for(std::chrono::duration<double>(std::min(gap(rng), 5.0)));
          const std::size_t k = next++ % kRobots;
          const double up = target[k] + kStep_mps <= range_low(k) + kRangeSpan_mps + 1e-9 ? kStep_mps : -kStep_mps;
          const double down_ok = target[k] - kStep_mps >= range_low(k) - 1e-9;
          const double step = (rng() % 2 == 0 && down_ok) ? -kStep_mps : up;
          target[k] = std::round((target[k] + step) / 0.001) * 0.001;
          const double wanted = as_carried(model_of(k), target[k], lease_s);
          const auto pressed = Clock::now();
          clients[k]->target(target[k], kAngular_radps);
          ++figures[k].presses;
          bool reached = false;
          for (const auto deadline = pressed + kPressTimeout; Clock::now() < deadline && !reached;
               std::this_thread::sleep_for(2ms)) {
            for (const auto& s : fleet.robot(k).samples(seen[k])) {
              ++seen[k];
              if (s.at >= pressed && std::abs(s.velocity.linear_mps - wanted) < 1e-6) {
                figures[k].press_ms.push_back(std::chrono::duration<double, std::milli>(s.at - pressed).count());
                reached = true;
                break;
              }
            }
          }
          figures[k].missed += reached ? 0 : 1;
        }
        const double driven_s = std::chrono::duration<double>(Clock::now() - started).count();
        // Lapses: the robot came to a standstill while its stream held a non-zero target.
        for (std::size_t k = 0; k < kRobots; ++k) {
          bool was_moving = true;
          for (const auto& s : fleet.robot(k).samples()) {
            const bool moving = s.velocity.linear_mps != 0 || s.velocity.angular_radps != 0;
            if (s.at >= started && was_moving && !moving) ++figures[k].lapses;
            was_moving = moving;
          }
          figures[k].joint = fleet.robot(k).renewals() - joint_before[k];
          const auto executed = fleet.robot(k).executed();
          for (std::size_t i = executed_before[k]; i < executed.size(); ++i) {
            const auto* v = std::get_if<command::Velocity>(&executed[i].second);
            if (!v) continue;
            ++figures[k].renewals;
            const double linear = command::linear_mps(model_of(k), *v);
            if (linear < range_low(k) - 0.005 || linear > range_low(k) + kRangeSpan_mps + 0.005) ++figures[k].wrong;
          }
        }
        for (auto& c : clients) c->close();
        nlohmann::json robots = nlohmann::json::array();
        std::printf("dtmf-bench-fleet-teleop: %zu robots, %s, lease %.2f s, %.0f s driven through %s\n", kRobots,
                    authenticated ? "keyed (own keys and the room key)" : "unkeyed", lease_s, driven_s, rir.c_str());
        std::printf("%-8s %12s %8s %9s %22s %7s %6s\n", "robot", "renewals/s", "joint/s", "presses",
                    "press->cmd_vel med/p95/max", "lapses", "wrong");
        for (std::size_t k = 0; k < kRobots; ++k) {
          const RobotFigures& f = figures[k];
          const double per_s = f.renewals / driven_s;
          const double joint_per_s = f.joint / driven_s;
          std::printf("%-8s %12.2f %8.2f %4d (%d missed) %6.0f/%4.0f/%4.0f ms %7d %6d\n", fleet.name(k).c_str(), per_s,
                      joint_per_s, f.presses, f.missed, percentile(f.press_ms, 0.5), percentile(f.press_ms, 0.95),
                      percentile(f.press_ms, 1.0), f.lapses, f.wrong);
          nlohmann::json r = {
              {"robot", fleet.name(k)}, {"renewals_per_s", per_s}, {"joint_renewals_per_s", joint_per_s},
              {"presses", f.presses},   {"missed", f.missed},      {"lapses", f.lapses},
              {"wrong", f.wrong}};
          r["press_to_cmd_vel_ms"] = summary(f.press_ms);
          robots.push_back(r);
        }
        // A lapse of every robot at once is the sender's: it waited for the air (another's sound
        // heard, or its own taken for another's), or its process stalled (no wait counted).
        const server::AirShare air = fleet.air_share();
        std::printf("the sender's air: %llu blocks of another's sound heard, %llu frames deferred, %llu yields\n",
                    static_cast<unsigned long long>(air.busy_blocks), static_cast<unsigned long long>(air.deferred),
                    static_cast<unsigned long long>(air.yields));
        std::vector<double> all_ms;
        for (const auto& f : figures) all_ms.insert(all_ms.end(), f.press_ms.begin(), f.press_ms.end());
        nlohmann::json out = {
            {"authenticated", authenticated}, {"seconds", driven_s}, {"lease_s", lease_s}, {"robots", robots}};
        out["press_to_cmd_vel_ms"] = summary(all_ms);
        out["air_busy_blocks"] = air.busy_blocks;
        out["air_deferred"] = air.deferred;
        out["air_yields"] = air.yields;
        out["rir"] = rir;
        out["measured_utc"] = utc_now_text();
        if (!json_path.empty()) write_json(json_path, out);
        return 0;
      },
      [](const std::string& what) { std::fprintf(stderr, "dtmf-bench-fleet-teleop: %s\n", what.c_str()); });
}
