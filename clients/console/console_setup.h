// dtmf-console's flags and its start: the channel to dtmf-server, the page's guard, and the
// web server that relays each page's calls (web_server.h, page_session.h).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "global_options.h"
#include "web_server.h"

namespace dtmf::console {

struct ConsoleFlags {
  cli::ServerOptions server;               // --server, --tls-ca, --token-file: as dtmfctl's
  std::string address = "127.0.0.1";       // --address: where the page is served
  int port = 8080;                         // --port
  std::string tls_cert, tls_key;           // --tls-cert, --tls-key: serve HTTPS
  std::string auth_token_file;             // --auth-token-file: the operator's token, for an address not loopback
  std::vector<std::string> allowed_hosts;  // --allowed-host: other names the page is opened by
  bool allow_anyone = false;               // --allow-anyone-on-the-network
  std::string assets;                      // --assets: the page's files
};

// Adds the flags; the page is looked for next to the binary (`program`, argv[0], when
// /proc/self/exe cannot be read): ../share/dtmf-teleop/console from its folder.
void add_console_flags(CLI::App& app, ConsoleFlags& flags, const std::string& program);

struct Console {
  std::unique_ptr<WebServer> web;
  std::string url;  // what to open in the browser
};

// Checks the flags (std::invalid_argument naming what is wrong and how to fix it) and starts.
// The server need not be up: each page's calls say so, and gRPC reconnects by itself.
std::unique_ptr<Console> start_console(const ConsoleFlags& flags);

}  // namespace dtmf::console
