// dtmf-server's command line: every flag, its environment variable and its default, read
// into ServerFlags (CLI11). main.cpp reads them and server_setup.h turns them into the
// server's parts; nothing here opens a file or a device.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <optional>
#include <string>

#include "audio_program.h"
#include "key_flags.h"

namespace dtmf::server {

struct ServerFlags {
  std::string address = "127.0.0.1";
  int port = 50051;
  std::string audio_out = "default";
  std::string audio_in = "default";
  std::string profile;  // empty: with a key the first profile that carries a MAC, else seed
  bool allow_unauthenticated = false;
  std::optional<std::string> db;
  std::string spill_file;
  std::string on_unconfirmed = "fail";
  double decision_timeout_s = 60;
  std::size_t max_queue = 32;
  std::string tls_cert, tls_key, auth_token_file;
  bool allow_anyone = false;
  program::KeyFlags keys;
  int robot_address = 0;
  std::string robot = "burger";
  std::string robot_name = "robot";
  std::string robots_file;
  std::string host;  // this sender's name in the database; empty: the machine's
  program::AudioProgramOptions program;
};

// Adds every flag of dtmf-server to `app`, reading into `f`, with its footer.
void add_server_flags(CLI::App& app, ServerFlags& f);

}  // namespace dtmf::server
