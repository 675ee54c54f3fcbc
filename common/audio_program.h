// What dtmf-agent and dtmf-server share around their own work: the options of a program
// that plays and records (--log-level, --list-audio-devices, --audio-buffer-ms) and the tail
// of main(): parse, set the log level, list the devices or run the body; every error one log
// line and an exit code (program_main.h). The physical layer takes the buffer depth as a
// parameter; this is where the flag and its environment variable live.
// Header-only: each program includes it once.
#pragma once

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <string>

#include "link/link.h"
#include "physical/portaudio_device.h"
#include "program_main.h"

namespace dtmf::program {

struct AudioProgramOptions {
  std::string log_level = "info";
  bool list_devices = false;
  physical::DeviceOptions devices;
  // How this program works without any sound device (its file flags), added to the
  // physical layer's "no audio device found".
  std::string without_devices;
};

inline void add_audio_program_options(CLI::App& app, AudioProgramOptions& options) {
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();
  app.add_flag("--list-audio-devices", options.list_devices, "list the audio devices and exit");
  app.add_option("--audio-buffer-ms", options.devices.buffer_ms,
                 "sound device buffer depth, each way: deeper survives a busier machine, shallower answers sooner")
      ->envname("DTMF_AUDIO_BUFFER_MS")
      ->check(CLI::Range(physical::kMinAudioBufferMs, physical::kMaxAudioBufferMs))
      ->capture_default_str();
}

// Parses, then runs `body` (or lists the devices); the exit code of the program.
inline int audio_program_main(CLI::App& app, int argc, char** argv, const AudioProgramOptions& options,
                              const std::function<int()>& body) {
  if (const auto exit_code = parse(app, argc, argv)) return *exit_code;
  spdlog::set_level(spdlog::level::from_str(options.log_level));
  // Before any receiver is built: its FFT plans come from the wisdom file, or are measured
  // once and saved there (protocol/signal/fft_wisdom.h).
  const std::string wisdom = link::plan_cache_default_file();
  link::use_plan_cache(wisdom);
  spdlog::debug("FFT wisdom: {}", wisdom.empty() ? "none (plans measured at every start)" : wisdom);
  return run(
      [&] {
        if (options.list_devices) {
          std::printf("%s", physical::format_device_list(physical::list_audio_devices()).c_str());
          return kExitOk;
        }
        try {
          return body();
        } catch (const physical::NoAudioDevice& e) {
          throw physical::AudioError(std::string(e.what()) + "; " + options.without_devices);
        }
      },
      [](const std::string& error) { spdlog::error("{}", error); });
}

}  // namespace dtmf::program
