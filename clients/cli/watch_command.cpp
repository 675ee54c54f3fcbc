// dtmfctl watch: the air as the sender puts it there and hears it (WatchAir), one line per
// event as it happens, until Ctrl-C, --count events or --seconds. dtmfctl heard: what robots
// heard and did, from the database (ListReceptions), and with --follow as it is stored.
#include <cstdio>

#include "offline_commands.h"
#include "server_connection.h"
#include "watch_view.h"

namespace dtmf::cli {

namespace {

struct WatchFlags {
  bool spectrum = false;
  double columns_per_s = 0;
  unsigned bins = 0;
  unsigned count = 0;  // 0: until the stream ends
  double seconds = 0;  // 0: no limit
};

int run_watch(const GlobalOptions& global, const WatchFlags& flags) {
  ServerConnection connection(global.server);
  auto context = connection.context();
  if (flags.seconds > 0)
    context->set_deadline(std::chrono::system_clock::now() +
                          std::chrono::milliseconds(static_cast<long long>(flags.seconds * 1000)));
  v1::WatchAirRequest request;
  request.set_robot(global.robot);
  request.set_spectrum(flags.spectrum);
  request.set_columns_per_s(flags.columns_per_s);
  request.set_bins(flags.bins);
  auto reader = connection.teleop().WatchAir(context.get(), request);
  v1::WatchAirResponse message;
  unsigned shown = 0;
  while (reader->Read(&message)) {
    const std::string text = global.json ? watch_json(message) : watch_lines(message);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    if (flags.count > 0 && ++shown >= flags.count) {
      context->TryCancel();
      break;
    }
  }
  const grpc::Status status = reader->Finish();
  // Its own end (--count, --seconds) is no error.
  if (status.ok() || status.error_code() == grpc::StatusCode::CANCELLED ||
      status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED)
    return 0;
  std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
  return exit_code_for(status);
}

struct HeardFlags {
  std::string run;  // an id, or a number
  unsigned limit = 0;
  bool follow = false;
};

int run_heard(const GlobalOptions& global, const HeardFlags& flags) {
  ServerConnection connection(global.server);
  auto context = connection.context();
  v1::ListReceptionsRequest request;
  request.set_robot(global.robot);
  request.set_limit(flags.limit);
  request.set_follow(flags.follow);
  if (!flags.run.empty() && flags.run.find_first_not_of("0123456789") == std::string::npos)
    request.set_run_number(std::stoll(flags.run));
  else if (!flags.run.empty())
    request.set_run_id(flags.run);
  auto reader = connection.teleop().ListReceptions(context.get(), request);
  v1::ListReceptionsResponse message;
  while (reader->Read(&message)) {
    const std::string text = global.json ? json_line(message.reception()) : reception_line(message.reception());
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
  }
  const grpc::Status status = reader->Finish();
  if (status.ok()) return 0;
  std::fprintf(stderr, "dtmfctl: %s\n", describe_status(status).c_str());
  return exit_code_for(status);
}

}  // namespace

void add_heard_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto flags = std::make_shared<HeardFlags>();
  CLI::App* heard = app.add_subcommand(
      "heard",
      "what the robots heard and did, from the database: executed, refused and why, heard again (--robot: one)");
  heard->add_option("--run", flags->run, "within this test run's time (its id or number); default: any time");
  heard->add_option("--limit", flags->limit, "the newest this many (default 100, at most 10000)")
      ->check(CLI::Range(0u, 10000u));
  heard->add_flag("--follow", flags->follow, "then each one as it is stored, until Ctrl-C");
  heard->callback([&run, &global, flags] { run = [&global, flags] { return run_heard(global, *flags); }; });
}

void add_watch_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto flags = std::make_shared<WatchFlags>();
  CLI::App* watch = app.add_subcommand(
      "watch", "watch the air as the server puts it there and hears it: frames, answers, waits (--robot: one robot's)");
  watch->add_flag("--spectrum", flags->spectrum, "also the microphone's spectrum, one line per column");
  watch->add_option("--columns-per-s", flags->columns_per_s, "spectrum columns a second (default 10, at most 50)")
      ->check(CLI::Range(0.0, 50.0));
  watch->add_option("--bins", flags->bins, "bins per spectrum column (default 128, at most 512)")
      ->check(CLI::Range(0u, 512u));
  watch->add_option("--count", flags->count, "stop after this many events");
  watch->add_option("--seconds", flags->seconds, "stop after this long")->check(CLI::NonNegativeNumber);
  watch->callback([&run, &global, flags] { run = [&global, flags] { return run_watch(global, *flags); }; });
}

}  // namespace dtmf::cli
