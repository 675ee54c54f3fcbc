#include "global_options.h"

namespace dtmf::cli {

void add_global_options(CLI::App& app, GlobalOptions& options, bool with_server) {
  // Subcommands copy this setting from their parent when they are added.
  app.fallthrough();
  app.add_flag("--json", options.json, "print JSON, one object per line (frames, progress events, runs, the report)")
      ->group("Connection and output (before or after the subcommand)");
  if (!with_server) return;
  app.add_option("--server", options.server.address, "dtmf-server address host:port (live commands)")
      ->envname("DTMF_SERVER")
      ->capture_default_str()
      ->group("Connection and output (before or after the subcommand)");
  app.add_option("--robot", options.robot,
                 "the robot to drive, by the name the server gives it (dtmfctl robots); default: the server's only one")
      ->envname("DTMF_ROBOT")
      ->group("Connection and output (before or after the subcommand)");
  app.add_option("--tls-ca", options.server.tls_ca,
                 "connect with TLS, trusting this PEM certificate (the server's or its CA's)")
      ->group("Connection and output (before or after the subcommand)");
  app.add_option("--token-file", options.server.token_file,
                 "send the bearer token in this file (dtmf-server --auth-token-file)")
      ->group("Connection and output (before or after the subcommand)");
}

}  // namespace dtmf::cli
