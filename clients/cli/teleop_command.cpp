// dtmfctl teleop: drive the robot live from the keyboard through dtmf-server's Teleop stream.
//
// One thread reads the server's status; this one reads keys, sends the target whenever it
// changes and repeats it ten times a second (as turtlebot3_teleop_key publishes), and
// redraws. Quitting (q, Ctrl-C) ends the stream and sends Stop, so the robot stops at once
// rather than when its lease ends; a killed dtmfctl leaves the lease to stop it.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <thread>

#include "offline_commands.h"
#include "server_connection.h"
#include "teleop_screen.h"

namespace dtmf::cli {

namespace {

struct TeleopOptions {
  ServerOptions server;
  std::string profile = "fast";
  double lease_s = 1.0;
  std::string robot;  // its name (dtmfctl --robot); empty: the server's only one
  std::string model;  // empty: the model the server gives the robot
};

constexpr int kRepeatMs = 100;

std::atomic<bool> interrupted{false};

void on_interrupt(int) { interrupted = true; }

v1::TeleopRequest request_for(const TeleopTarget& target, const TeleopOptions& o, bool first) {
  v1::TeleopRequest r;
  r.set_linear_mps(target.linear_mps);
  r.set_angular_radps(target.angular_radps);
  r.set_lease_s(o.lease_s);
  if (first) {
    r.mutable_options()->set_profile(o.profile);
    r.mutable_options()->set_robot(o.robot);
  }
  return r;
}

// The Stop goes out with the stream's profile: the robot answers it as fast as it answered
// the stream's frames.
int send_stop(ServerConnection& connection, const TeleopOptions& o, bool every_robot) {
  v1::StopRequest stop;
  stop.mutable_options()->set_profile(o.profile);
  if (every_robot)
    stop.set_all_robots(true);
  else
    stop.mutable_options()->set_robot(o.robot);
  auto context = connection.context();
  auto reader = connection.teleop().Stop(context.get(), stop);
  v1::StopResponse ignored;
  while (reader->Read(&ignored)) {
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok()) std::fprintf(stderr, "dtmfctl: the stop: %s\n", describe_status(status).c_str());
  return exit_code_for(status);
}

// The model the server gives the robot (ListRobots); the keys' steps stay within its limits.
std::string model_of(ServerConnection& connection, const TeleopOptions& o) {
  v1::ListRobotsResponse robots;
  auto context = connection.context();
  const grpc::Status status = connection.teleop().ListRobots(context.get(), {}, &robots);
  // A server from before ListRobots drives one robot of its --robot model: say which with --model.
  if (status.error_code() == grpc::StatusCode::UNIMPLEMENTED) return "burger";
  if (!status.ok()) throw std::runtime_error("the server's robots: " + describe_status(status));
  for (const v1::Robot& r : robots.robots()) {
    if (r.name() == o.robot || (o.robot.empty() && robots.robots_size() == 1)) return r.model();
  }
  // The server names what is wrong when the stream opens (options.robot).
  return "burger";
}

int run_teleop(const TeleopOptions& o) {
  if (!::isatty(STDIN_FILENO) || !::isatty(STDOUT_FILENO)) {
    throw std::invalid_argument(
        "teleop needs a terminal to read keys from and draw on (stdin and stdout are not both terminals); "
        "from a script, use the Python client's Client.teleop() or the Teleop RPC");
  }
  ServerConnection connection(o.server);
  const command::RobotModel& model = command::robot_model_by_name(o.model.empty() ? model_of(connection, o) : o.model);
  auto context = connection.context();
  auto stream = connection.teleop().Teleop(context.get());

  TeleopView view{o.server.address, o.profile, model.name, o.lease_s, {}, std::nullopt, {}};
  std::mutex mutex;  // guards view.status
  std::thread reader([&] {
    v1::TeleopResponse response;
    while (stream->Read(&response)) {
      std::lock_guard lock(mutex);
      view.status = response;
    }
  });

  interrupted = false;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  bool stream_open = stream->Write(request_for(view.target, o, true));
  bool every_robot = false;  // e: stop every robot in the room
  {
    TeleopScreen screen;
    auto last_sent = std::chrono::steady_clock::now();
    while (stream_open && !interrupted) {
      const auto key = screen.key(kRepeatMs / 2);
      bool changed = false;
      if (key) {
        const KeyEffect effect = apply_key(*key, view.target, model);
        every_robot = effect == KeyEffect::StopEveryRobot;
        if (effect == KeyEffect::Quit || every_robot) break;
        changed = effect == KeyEffect::Changed;
      }
      const auto now = std::chrono::steady_clock::now();
      if (changed || now - last_sent >= std::chrono::milliseconds(kRepeatMs)) {
        stream_open = stream->Write(request_for(view.target, o, false));
        last_sent = now;
      }
      std::lock_guard lock(mutex);
      screen.draw(view);
    }
    view.note = every_robot ? "stopping every robot in the room ..." : "stopping the robot ...";
    std::lock_guard lock(mutex);
    screen.draw(view);
  }
  // An emergency goes out before anything else; it also ends this stream (ABORTED).
  const int stopped_all = every_robot ? send_stop(connection, o, true) : 0;
  stream->WritesDone();
  reader.join();
  const grpc::Status status = stream->Finish();
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  if (every_robot) {
    std::printf("teleop ended; a stop for every robot sent (%s)\n", stopped_all == 0 ? "played" : "refused");
    return stopped_all;
  }
  const int stopped = send_stop(connection, o, false);
  if (!status.ok()) {
    std::fprintf(stderr, "dtmfctl: teleop: %s\n", describe_status(status).c_str());
    return exit_code_for(status);
  }
  std::printf("teleop ended; Stop sent (%s)\n", stopped == 0 ? "confirmed" : "not confirmed");
  return stopped;
}

}  // namespace

void add_teleop_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<TeleopOptions>();
  CLI::App* teleop = app.add_subcommand(
      "teleop",
      "drive live from the keyboard (turtlebot3_teleop_key's keys: w/x linear, a/d angular, s/space stop, q quit; "
      "e stops every robot in the room)");
  teleop->add_option("--profile", o->profile, "link profile; it must carry velocity commands (fast)")
      ->envname("DTMF_PROFILE")
      ->capture_default_str();
  teleop->add_option("--lease-s", o->lease_s, "how long the robot holds a target without a renewal (0.3..2)")
      ->check(CLI::Range(0.3, 2.0))
      ->capture_default_str();
  teleop
      ->add_option("--model", o->model,
                   "TurtleBot3 model (its limits bound the keys' steps); default: the model the server gives the robot")
      ->check(CLI::IsMember({"burger", "waffle", "waffle_pi"}));
  teleop->callback([o, &global, &run] {
    run = [o, &global] {
      o->server = global.server;
      o->robot = global.robot;
      return run_teleop(*o);
    };
  });
}

}  // namespace dtmf::cli
