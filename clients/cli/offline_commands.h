// dtmfctl's offline subcommands: they run the link's layers on files, no server needed.
//
//   encode    command or word -> frames (word, frame bits, CRC, tones), optionally a WAV
//   decode    WAV -> the robot's receive path -> frames found, CRC verdicts, commands
//   simulate  WAV -> the simulated acoustic channel (distance, noise, room, clock) -> WAV
//   keygen    a new link key file (mode 0600)
//
// Each add_* function registers its subcommand on `app` and sets `run` to the action that
// executes it after parsing; the action reads `global` (--json, the server) when it runs.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

#include "global_options.h"

namespace dtmf::cli {

using Action = std::function<int()>;

void add_encode_command(CLI::App& app, Action& run, const GlobalOptions& global);
void add_decode_command(CLI::App& app, Action& run, const GlobalOptions& global);
void add_simulate_command(CLI::App& app, Action& run, const GlobalOptions& global);
void add_keygen_command(CLI::App& app, Action& run, const GlobalOptions& global);

// Live subcommands (through dtmf-server): drive, turn, stop, reset, sequence (live_commands.cpp);
// runs, report, health (report_view.cpp).
void add_live_commands(CLI::App& app, Action& run, const GlobalOptions& global);
void add_run_commands(CLI::App& app, Action& run, const GlobalOptions& global);
// teleop: live driving from the keyboard in a full-screen view (teleop_command.cpp).
void add_teleop_command(CLI::App& app, Action& run, const GlobalOptions& global);
// watch: the air as the server puts it there and hears it (watch_command.cpp).
void add_watch_command(CLI::App& app, Action& run, const GlobalOptions& global);
// heard: what the robots heard and did, from the database (watch_command.cpp).
void add_heard_command(CLI::App& app, Action& run, const GlobalOptions& global);

}  // namespace dtmf::cli
