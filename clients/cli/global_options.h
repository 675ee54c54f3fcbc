// dtmfctl's options that belong to no one subcommand: how to reach the server (--server,
// --tls-ca, --token-file), which of its robots to drive (--robot) and --json. They are the top-level app's, and every
// subcommand falls through to it, so they work before or after the subcommand (as with kubectl, git or grpcurl) and
// --help lists them once. Plain data: the offline commands need no gRPC.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace dtmf::cli {

struct ServerOptions {
  std::string address = "localhost:50051";
  std::string tls_ca;      // PEM of the CA (or the server's own certificate): use TLS
  std::string token_file;  // bearer token
};

struct GlobalOptions {
  ServerOptions server;
  std::string robot;  // --robot NAME: the robot a command is for (empty: the server's only one)
  bool json = false;  // one JSON object per line, in every subcommand that prints
};

// Adds the options to `app` and lets every subcommand added afterwards fall through to it.
// Without `with_server` (a dtmfctl built without its live commands) only --json.
void add_global_options(CLI::App& app, GlobalOptions& options, bool with_server = true);

}  // namespace dtmf::cli
