// dtmfctl: the command-line client of dtmf-teleop.
//
// Exit codes: 0 success, 1 a runtime error (unreadable file, bad audio), 2 bad usage.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "offline_commands.h"
#include "program_main.h"
#include "profile/link_profile.h"

int main(int argc, char** argv) {
  CLI::App app{"dtmfctl: drive a TurtleBot3 by sound, and inspect the acoustic link offline.\n"
               "Link profiles: " + dtmf::profile_names()};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 runtime error (unreadable file, bad audio), 2 bad usage.\n"
      "Examples:\n"
      "  dtmfctl encode --json --word 2861\n"
      "  dtmfctl encode --wav drive.wav drive --speed 50 --duration 3\n"
      "  dtmfctl simulate drive.wav heard.wav --distance 4 --noise white --noise-dbfs -40\n"
      "  dtmfctl decode --json heard.wav");

  dtmf::cli::Action run;
  dtmf::cli::add_encode_command(app, run);
  dtmf::cli::add_decode_command(app, run);
  dtmf::cli::add_simulate_command(app, run);

  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  return dtmf::program::run(run, [](const std::string& error) { std::fprintf(stderr, "dtmfctl: %s\n", error.c_str()); });
}
