// dtmfctl: the command-line client of dtmf-teleop.
//
// Exit codes: 0 success / confirmed, 1 a runtime error (unreadable file, bad audio), 2 bad usage,
// 3 the robot did not confirm or the command failed, 4 the server cannot be reached.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "offline_commands.h"
#include "server_connection.h"
#include "program_main.h"
#include "profile/link_profile.h"

int main(int argc, char** argv) {
  CLI::App app{"dtmfctl: drive a TurtleBot3 by sound, and inspect the acoustic link offline.\n"
               "Link profiles: " + dtmf::profile_names()};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success (command confirmed), 1 runtime error (unreadable file, bad audio), 2 bad usage,\n"
      "            3 the robot did not confirm / the command failed, 4 the server cannot be reached.\n"
      "Examples:\n"
      "  dtmfctl encode --json --word 2861\n"
      "  dtmfctl encode --wav drive.wav drive --speed 50 --duration 3\n"
      "  dtmfctl simulate drive.wav heard.wav --distance 4 --noise white --noise-dbfs -40\n"
      "  dtmfctl decode --json heard.wav\n"
      "  dtmfctl decode --replies --profile fast answers.wav   (the ACKs and NACKs a sender would hear)\n"
      "  dtmfctl drive --speed 50 --duration 2          (through dtmf-server: --server, DTMF_SERVER)\n"
      "  dtmfctl sequence --label general\n"
      "  dtmfctl report --json");

  dtmf::cli::Action run;
  dtmf::cli::GlobalOptions global;
  dtmf::cli::add_global_options(app, global);  // before the subcommands, which fall through to it
  dtmf::cli::add_encode_command(app, run, global);
  dtmf::cli::add_decode_command(app, run, global);
  dtmf::cli::add_simulate_command(app, run);
  dtmf::cli::add_live_commands(app, run, global);
  dtmf::cli::add_run_commands(app, run, global);

  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  const auto report = [](const std::string& error) { std::fprintf(stderr, "dtmfctl: %s\n", error.c_str()); };
  return dtmf::program::run(
      [&] {
        try {
          return run();
        } catch (const dtmf::cli::Unreachable& e) {
          report(e.what());
          return dtmf::cli::kExitUnreachable;
        }
      },
      report);
}
