// What every dtmf-teleop program's main() shares: the exit codes (0 success, 1 something
// needed could not be had, 2 bad usage) applied to CLI11 parsing and to the program's body.
// Log lines go to standard error in every program, so that standard output holds only what a
// program prints on purpose (with --json, JSON lines alone; spdlog's default writes to
// standard output). Header-only: each program includes it once.
#pragma once

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace dtmf::program {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// Parses the command line; the exit code to leave with when that is all (help or --version:
// 0, a bad flag: 2 after CLI11 has said what was wrong), nothing when the program should go on.
inline std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  auto& sinks = spdlog::default_logger()->sinks();
  sinks.assign({std::make_shared<spdlog::sinks::stderr_color_sink_mt>()});
  const std::string program = argc > 0 ? std::filesystem::path(argv[0]).filename().string() : "dtmf-teleop";
  app.set_version_flag("--version", program + " " + DTMF_VERSION, "print the version and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  return std::nullopt;
}

// Runs the body; a std::invalid_argument (a bad value) exits 2, any other error 1, each
// reported through `report` — one clear line, never a crash.
inline int run(const std::function<int()>& body, const std::function<void(const std::string&)>& report) {
  try {
    return body();
  } catch (const std::invalid_argument& e) {
    report(e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    report(e.what());
    return kExitFailure;
  }
}

}  // namespace dtmf::program
