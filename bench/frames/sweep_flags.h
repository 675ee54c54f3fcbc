// The flags every frame-success sweep shares (SweepOptions, sweep.h): how many frames, in
// streams of how many, the seed and the threads, and with a stream of blocks the receiver's
// feed size. One definition for dtmf-bench-snr, dtmf-bench-distance and dtmf-bench-rooms.
// Header-only, like the programs' other flag helpers.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "frames/sweep.h"

namespace dtmf::bench {

// `--frames` reads "frames per `unit`" (a point, a case). Call where the frame count's flag
// belongs in --help; the rest follow it.
inline void add_sweep_flags(CLI::App& app, SweepOptions& options, const std::string& unit, bool block_samples) {
  app.add_option("--frames", options.frames, "frames per " + unit)->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--chunk-frames", options.chunk_frames, "frames per continuous stream")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  if (block_samples) {
    app.add_option("--block-samples", options.block_samples, "receiver feed size")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  }
  app.add_option("--seed", options.seed, "random seed (frame contents and noise)")->capture_default_str();
  app.add_option("--threads", options.threads, "worker threads")->capture_default_str()->check(CLI::PositiveNumber);
}

}  // namespace dtmf::bench
