// dtmfctl runs / report / health, and the seed's Appendix A table for a run's report.
#pragma once

#include <string>

#include "offline_commands.h"
#include "server_connection.h"

namespace dtmf::cli {

// Prints the report of `run_id` as the seed's table; a note instead if there is none.
void print_report_of(ServerConnection& connection, const std::string& run_id);

void add_run_commands(CLI::App& app, Action& run);

}  // namespace dtmf::cli
