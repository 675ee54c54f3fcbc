// dtmfctl watch: the air as the sender puts it there and hears it (WatchAir), one line per
// event as it happens, until Ctrl-C, --count events or --seconds.
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

}  // namespace

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
