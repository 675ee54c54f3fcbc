// dtmfctl drive / turn / stop / reset / sequence: commands through dtmf-server, with live
// progress and the seed's prompt for a frame left unconfirmed after the automatic retry.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "offline_commands.h"
#include "profile/link_profile.h"
#include "progress_view.h"
#include "report_view.h"
#include "server_connection.h"

namespace dtmf::cli {

namespace {

struct LiveOptions {
  ServerOptions server;
  bool json = false;
  std::string on_unconfirmed = "fail";
  std::string profile;  // empty: the server's default
  std::string robot;    // empty: the server's only robot
  std::optional<double> speed, rotation, duration;
  std::string label, notes;
  bool all_robots = false;  // stop: every robot in the room
};

// With a person at the terminal the server asks (and we ask them); otherwise the flag decides.
v1::CommandOptions command_options(const LiveOptions& o) {
  v1::CommandOptions options;
  if (::isatty(STDIN_FILENO))
    options.set_on_unconfirmed(v1::UNCONFIRMED_POLICY_ASK);
  else
    options.set_on_unconfirmed(o.on_unconfirmed == "continue" ? v1::UNCONFIRMED_POLICY_CONTINUE
                                                              : v1::UNCONFIRMED_POLICY_FAIL);
  options.set_profile(o.profile);
  options.set_robot(o.robot);
  return options;
}

// The seed's prompt (its section 7) offers two choices: continue as if acknowledged, or send
// again. Abort is ours, for a person who would rather stop than guess.
v1::Decision ask_person(const v1::Progress& p) {
  while (true) {
    std::fprintf(stderr,
                 "%s\nContinuing without a confirmation may make the robot do something unexpected.\n"
                 "[c]ontinue / [r]etransmit / [a]bort? ",
                 p.detail().c_str());
    std::string answer;
    if (!std::getline(std::cin, answer)) return v1::DECISION_ABORT;
    if (answer == "c" || answer == "continue") return v1::DECISION_CONTINUE;
    if (answer == "r" || answer == "retransmit") return v1::DECISION_RETRANSMIT;
    if (answer == "a" || answer == "abort") return v1::DECISION_ABORT;
  }
}

template <class Response, class Call>
int stream(ServerConnection& connection, ProgressView& view, Call call,
           const std::function<std::optional<SequencePosition>(const Response&)>& position = {}) {
  auto context = connection.context();
  auto reader = call(*context);
  Response response;
  while (reader->Read(&response)) {
    const v1::Progress& p = response.progress();
    view.show(p, position ? position(response) : std::nullopt);
    if (p.event() == v1::FRAME_EVENT_AWAITING_DECISION && ::isatty(STDIN_FILENO)) {
      view.finish_line();
      v1::DecideRequest decide;
      decide.set_command_id(p.command_id());
      decide.set_decision(ask_person(p));
      v1::DecideResponse ignored;
      auto decide_context = connection.context();
      const grpc::Status decided = connection.teleop().Decide(decide_context.get(), decide, &ignored);
      if (!decided.ok()) std::fprintf(stderr, "dtmfctl: %s\n", describe_status(decided).c_str());
    }
  }
  view.finish_line();
  const grpc::Status status = reader->Finish();
  if (!status.ok()) std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
  return exit_code_for(status);
}

int run_live(const std::string& kind, const LiveOptions& o) {
  ServerConnection connection(o.server);
  ProgressView view(o.json, ::isatty(STDOUT_FILENO));
  auto& teleop = connection.teleop();
  if (kind == "drive") {
    v1::DriveRequest r;
    r.set_speed_percent(*o.speed);
    if (o.duration) r.set_duration_s(*o.duration);
    *r.mutable_options() = command_options(o);
    return stream<v1::DriveResponse>(connection, view, [&](grpc::ClientContext& c) { return teleop.Drive(&c, r); });
  }
  if (kind == "turn") {
    v1::TurnRequest r;
    r.set_rotation_percent(*o.rotation);
    if (o.duration) r.set_duration_s(*o.duration);
    *r.mutable_options() = command_options(o);
    return stream<v1::TurnResponse>(connection, view, [&](grpc::ClientContext& c) { return teleop.Turn(&c, r); });
  }
  if (kind == "stop") {
    v1::StopRequest r;
    *r.mutable_options() = command_options(o);
    if (o.all_robots) {
      if (!o.robot.empty()) {
        std::fprintf(stderr, "dtmfctl: stop --all stops every robot; drop --robot %s\n", o.robot.c_str());
        return 2;
      }
      r.set_all_robots(true);
    }
    return stream<v1::StopResponse>(connection, view, [&](grpc::ClientContext& c) { return teleop.Stop(&c, r); });
  }
  if (kind == "reset") {
    v1::ResetRequest r;
    *r.mutable_options() = command_options(o);
    return stream<v1::ResetResponse>(connection, view, [&](grpc::ClientContext& c) { return teleop.Reset(&c, r); });
  }
  v1::RunTestSequenceRequest r;
  r.set_label(o.label);
  r.set_notes(o.notes);
  *r.mutable_options() = command_options(o);
  std::string run_id;
  const int code = stream<v1::RunTestSequenceResponse>(
      connection, view, [&](grpc::ClientContext& c) { return teleop.RunTestSequence(&c, r); },
      [&](const v1::RunTestSequenceResponse& s) {
        run_id = s.run_id();
        return std::optional<SequencePosition>(SequencePosition{s.run_id(), s.frames_done(), s.frames_total()});
      });
  if (run_id.empty() || o.json) return code;
  std::printf("\n");
  print_report_of(connection, run_id);
  return code;
}

}  // namespace

void add_live_commands(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<LiveOptions>();
  const auto common = [&](CLI::App* command) {
    command
        ->add_option("--on-unconfirmed", o->on_unconfirmed,
                     "without a terminal to ask: fail or continue when a frame stays unconfirmed")
        ->check(CLI::IsMember({"fail", "continue"}))
        ->capture_default_str();
    command
        ->add_option("--profile", o->profile,
                     "link profile to send with: " + profile_names() + " (default: the server's --profile)")
        ->envname("DTMF_PROFILE");
    command->callback([o, command, &global, &run] {
      run = [o, &global, kind = command->get_name()] {
        o->server = global.server;
        o->robot = global.robot;
        o->json = global.json;  // one JSON object per progress event
        return run_live(kind, *o);
      };
    });
  };
  CLI::App* drive =
      app.add_subcommand("drive", "drive forward (DRIVE_FOR_DURATION with --duration, else DRIVE_FORWARD)");
  drive->add_option("--speed", o->speed, "percent of the robot's top speed, 0..100")->required();
  drive->add_option("--duration", o->duration, "seconds, 0..8");
  common(drive);
  CLI::App* turn = app.add_subcommand("turn", "turn on the spot (TURN_FOR_DURATION with --duration, else TURN)");
  turn->add_option("--rotation", o->rotation, "percent of the top turn rate, -100..100, positive turns left")
      ->required();
  turn->add_option("--duration", o->duration, "seconds, 0..8");
  common(turn);
  CLI::App* stop = app.add_subcommand("stop", "stop the robot now (goes ahead of queued commands)");
  stop->add_flag("--all", o->all_robots,
                 "every robot in the room, whatever this server drives: one frame each robot executes and none "
                 "answers (with keyed robots, under the room key: dtmf-server --room-key)");
  common(stop);
  common(app.add_subcommand("reset", "reset the robot's command state (RESET)"));
  CLI::App* sequence =
      app.add_subcommand("sequence", "run the seed's 65-frame test sequence as a labelled run, then print its report");
  sequence->add_option("--label", o->label, "the run's label: general, noise, 4 m, ...")->required();
  sequence->add_option("--notes", o->notes, "free text kept with the run");
  common(sequence);
}

}  // namespace dtmf::cli
