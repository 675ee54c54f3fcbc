// dtmf-server's flags (server_flags.h), in three groups: where it serves, what it sends and
// where it logs; who may call it; and which robots it drives.
#include "server_flags.h"

#include "profile/link_profile.h"
#include "robot_roster.h"

namespace dtmf::server {

namespace {

// Who may call it: TLS, a token, or anyone.
void add_caller_flags(CLI::App& app, ServerFlags& f) {
  app.add_option("--tls-cert", f.tls_cert, "PEM certificate: serve TLS (with --tls-key)")
      ->envname("DTMF_SERVER_TLS_CERT");
  app.add_option("--tls-key", f.tls_key, "PEM private key")->envname("DTMF_SERVER_TLS_KEY");
  app.add_option("--auth-token-file", f.auth_token_file,
                 "every call must carry 'authorization: Bearer <token in this file>'")
      ->envname("DTMF_SERVER_AUTH_TOKEN_FILE");
  app.add_flag("--allow-anyone-on-the-network", f.allow_anyone,
               "serve an address off this machine without TLS and a token: anyone who reaches the port can drive "
               "the robot (a warning at start)")
      ->envname("DTMF_SERVER_ALLOW_ANYONE_ON_THE_NETWORK");
}

// Where it listens, what it plays and hears, how commands go out, and where they are logged.
void add_sending_flags(CLI::App& app, ServerFlags& f) {
  app.add_option("--address", f.address,
                 "address to listen on; off this machine only with TLS and a token, or --allow-anyone-on-the-network")
      ->envname("DTMF_SERVER_ADDRESS")
      ->capture_default_str();
  app.add_option("--port", f.port, "port to listen on (0: any free one)")
      ->check(CLI::Range(0, 65535))
      ->envname("DTMF_SERVER_PORT")
      ->capture_default_str();
  app.add_option("--audio-out", f.audio_out,
                 "loudspeaker: a device name or index, default, or wav:FILE (write what would be played)")
      ->envname("DTMF_SERVER_AUDIO_OUT")
      ->capture_default_str();
  app.add_option("--audio-in", f.audio_in,
                 "microphone for the robot's ACK / NACK: a device, default, wav:FILE, or none")
      ->envname("DTMF_SERVER_AUDIO_IN")
      ->capture_default_str();
  app.add_option("--profile", f.profile,
                 "link profile of commands that name none (CommandOptions.profile): " + profile_names() +
                     "; default: with --key the first that carries a MAC (fast), else seed")
      ->envname("DTMF_SERVER_PROFILE");
  app.add_flag("--allow-unauthenticated-commands", f.allow_unauthenticated,
               "with --key: let commands name a profile without a MAC (seed); their untagged ACKs are reported as "
               "unauthenticated (a warning at every start). Stop always goes authenticated")
      ->envname("DTMF_SERVER_ALLOW_UNAUTHENTICATED_COMMANDS");
  app.add_option("--db", f.db,
                 "PostgreSQL URL, or none; default: DTMF_DB_URL, else the libpq environment (PGHOST, ...)")
      ->envname("DTMF_DB_URL");
  app.add_option("--spill-file", f.spill_file, "where log rows wait while the database is away");
  app.add_option("--host", f.host,
                 "name of this sender in the database (default: hostname); give each server in a room its own")
      ->envname("DTMF_SERVER_HOST");
  app.add_option("--on-unconfirmed", f.on_unconfirmed,
                 "default policy for a frame unconfirmed after the automatic retry")
      ->check(CLI::IsMember({"ask", "continue", "fail"}))
      ->capture_default_str();
  app.add_option("--decision-timeout-s", f.decision_timeout_s, "with ask: how long to wait for Decide")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  app.add_option("--max-queue", f.max_queue, "commands that may wait; more get RESOURCE_EXHAUSTED")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
}

// The robots it drives and their keys: one robot by flags, or several by --robots.
void add_robot_flags(CLI::App& app, ServerFlags& f) {
  program::add_key_flags(app, f.keys, "DTMF_SERVER", "/var/lib/dtmf-server");
  program::add_room_key_flag(app, f.keys, "DTMF_SERVER");
  auto* robots = app.add_option("--robots", f.robots_file,
                                "several robots: a JSON list of {name, address, key, model} (docs/protocol.md §9); "
                                "instead of --robot-name, --robot-address, --key and --robot")
                     ->envname("DTMF_SERVER_ROBOTS_FILE")
                     ->check(CLI::ExistingFile);
  app.add_option("--robot-name", f.robot_name, "the one robot's name (commands name it: dtmfctl --robot)")
      ->envname("DTMF_SERVER_ROBOT_NAME")
      ->check([](const std::string& name) {
        return robot_name_valid(name) ? std::string() : "1 to 32 letters, digits, - or _";
      })
      ->capture_default_str()
      ->excludes(robots);
  app.add_option("--robot-address", f.robot_address, "the robot's address (0..7, dtmf-agent --address)")
      ->envname("DTMF_SERVER_ROBOT_ADDRESS")
      ->check(CLI::Range(0, 7))
      ->capture_default_str()
      ->excludes(robots);
  app.get_option("--key")->excludes(robots);
  app.add_option("--robot", f.robot,
                 "TurtleBot3 model driven (as dtmf-agent --robot): Teleop's speeds are fractions of its limits")
      ->envname("TURTLEBOT3_MODEL")
      ->check(CLI::IsMember({"burger", "waffle", "waffle_pi"}))
      ->capture_default_str();
}

}  // namespace

void add_server_flags(CLI::App& app, ServerFlags& f) {
  // In this order in --help: the order they were always listed in.
  add_sending_flags(app, f);
  add_caller_flags(app, f);
  add_robot_flags(app, f);
  program::add_audio_program_options(app, f.program);
  f.program.without_devices =
      "or run without a sound card: --audio-out wav:FILE --audio-in none (scripts/air start "
      "gives a private PulseAudio)";
  app.footer(
      "Exit codes: 0 stopped cleanly, 1 an audio device, the database or the port could not be had, 2 bad usage.\n"
      "SIGINT / SIGTERM: health goes NOT_SERVING, the chord on air finishes, queued commands end UNAVAILABLE.");
}

}  // namespace dtmf::server
