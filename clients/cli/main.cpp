// dtmfctl: the command-line client of dtmf-teleop.
//
// Exit codes: 0 success / confirmed, 1 a runtime error (unreadable file, bad audio), 2 bad usage,
// 3 the robot did not confirm or the command failed, 4 the server cannot be reached, 5 the
// server refused the caller (no or wrong bearer token: UNAUTHENTICATED; PERMISSION_DENIED).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#ifndef DTMF_CLI_LIVE
#define DTMF_CLI_LIVE 0
#endif
#ifndef DTMF_CLI_SIMULATE
#define DTMF_CLI_SIMULATE 0
#endif

#include "link/link.h"
#include "offline_commands.h"
#include "profile/link_profile.h"
#include "program_main.h"
#if DTMF_CLI_LIVE
#include "server_connection.h"
#endif

namespace {
// The exit codes and examples, under --help.
constexpr const char* kFooter =
    "Exit codes: 0 success (command confirmed), 1 runtime error (unreadable file, bad audio), 2 bad usage,\n"
    "            3 the robot did not confirm / the command failed, 4 the server cannot be reached,\n"
    "            5 the server refused the caller (no or wrong bearer token: --token-file; not allowed).\n"
    "Examples:\n"
    "  dtmfctl encode --json --word 2861\n"
    "  dtmfctl encode --wav drive.wav drive --speed 50 --duration 3\n"
    "  dtmfctl simulate drive.wav heard.wav --distance 4 --noise white --noise-dbfs -40\n"
    "  dtmfctl decode --json heard.wav\n"
    "  dtmfctl keygen link.key                         (then dtmf-server --key link.key, dtmf-agent --key link.key)\n"
    "  dtmfctl encode --key link.key --profile fast --wav f.wav drive --speed 40   (authenticated frames)\n"
    "  dtmfctl decode --replies --profile fast answers.wav   (the ACKs and NACKs a sender would hear)\n"
    "  dtmfctl drive --speed 50 --duration 2          (through dtmf-server: --server, DTMF_SERVER)\n"
    "  dtmfctl sequence --label general\n"
    "  dtmfctl teleop                                  (drive live from the keyboard; fast profile)\n"
    "  dtmfctl robots; dtmfctl --robot beta drive --speed 30   (a server that drives several robots)\n"
    "  dtmfctl watch --robot beta                      (the air, live: frames, answers, waits)\n"
    "  dtmfctl heard --follow                          (what the robots heard and did, as it is logged)\n"
    "  dtmfctl report --json";
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "dtmfctl: drive a TurtleBot3 by sound, and inspect the acoustic link offline.\n"
      "Link profiles: " +
      dtmf::profile_names()};
  app.require_subcommand(1);
  app.footer(kFooter);

  dtmf::cli::Action run;
  dtmf::cli::GlobalOptions global;
  // Before the subcommands, which fall through to it.
  dtmf::cli::add_global_options(app, global, /*with_server=*/DTMF_CLI_LIVE);
  dtmf::cli::add_encode_command(app, run, global);
  dtmf::cli::add_decode_command(app, run, global);
#if DTMF_CLI_SIMULATE
  dtmf::cli::add_simulate_command(app, run, global);
#else
  app.footer(app.get_footer() + "\nThis dtmfctl was built without the simulator (cmake -DDTMF_BUILD_SIMULATOR=OFF).");
#endif
  dtmf::cli::add_keygen_command(app, run, global);
#if DTMF_CLI_LIVE
  dtmf::cli::add_live_commands(app, run, global);
  dtmf::cli::add_run_commands(app, run, global);
  dtmf::cli::add_teleop_command(app, run, global);
  dtmf::cli::add_watch_command(app, run, global);
  dtmf::cli::add_heard_command(app, run, global);
#else
  app.footer(app.get_footer() + "\nThis dtmfctl was built without its live commands (cmake -DDTMF_CLI_LIVE=OFF).");
#endif

  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  // decode builds receivers: their FFT plans come from the plan cache (link.h).
  dtmf::link::use_plan_cache(dtmf::link::plan_cache_default_file());
  const auto report = [](const std::string& error) { std::fprintf(stderr, "dtmfctl: %s\n", error.c_str()); };
  return dtmf::program::run(
      [&] {
#if DTMF_CLI_LIVE
        try {
          return run();
        } catch (const dtmf::cli::Unreachable& e) {
          report(e.what());
          return dtmf::cli::kExitUnreachable;
        }
#else
        return run();
#endif
      },
      report);
}
