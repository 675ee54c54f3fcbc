// dtmf-console: the web console. A client of dtmf-server's public API like dtmfctl (every
// thing the page shows or does is a call of dtmf.v1.TeleopService, relayed), and a web server
// for one page on this machine. See docs/console.md.
//
//   dtmf-console [--server localhost:50051] [--port 8080]
//
// It listens on loopback unless told otherwise; another address needs HTTPS and the
// operator's token (--tls-cert, --tls-key, --auth-token-file), or the warned flag.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>

#include "console_setup.h"
#include "program_main.h"

int main(int argc, char** argv) {
  using namespace dtmf;
  CLI::App app("dtmf-console: the web console of dtmf-teleop (the air live, the robots, driving, the report)");
  console::ConsoleFlags flags;
  console::add_console_flags(app, flags, argc > 0 ? argv[0] : "dtmf-console");
  if (const auto done = program::parse(app, argc, argv)) return *done;
  return program::run(
      [&] {
        // The signals that end it are taken by sigwait below, so every thread started from
        // here on (civetweb's, gRPC's) inherits them blocked.
        sigset_t ending;
        sigemptyset(&ending);
        sigaddset(&ending, SIGINT);
        sigaddset(&ending, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &ending, nullptr);
        const auto running = console::start_console(flags);
        std::cout << "console at " << running->url << std::endl;
        spdlog::info("console at {} (dtmf-server {}); Ctrl-C ends it", running->url, flags.server.address);
        int signal = 0;
        sigwait(&ending, &signal);
        spdlog::info("console: stopping ({})", signal == SIGINT ? "SIGINT" : "SIGTERM");
        return program::kExitOk;
      },
      [](const std::string& why) { spdlog::error("dtmf-console: {}", why); });
}
