// One continuous stream of random frames through a channel, scored slot by slot.
//
// Frames follow each other at their normal spacing (chord, then gap: one slot each). Each
// slot's clean audio goes through the channel (noise, a room), and the receiver is fed what
// comes out in fixed blocks (1024 samples by default), as a sound device delivers it; one
// more slot without a frame lets late or echoed detections show. An accepted frame belongs
// to the slot in which it started, a slot reaching from half its silence before its frame
// to half its silence after it (start estimates run a little early, or late by most of a
// drowned seed chord); under a clock offset, in the sender's time (the channel's ratio of
// samples heard to samples given).
// Definitions (docs/benchmarks.md):
//   success       the slot's frame was accepted exactly once with the right bits;
//   wrong accept  an accepted (check-passing) frame whose bits were not sent in its slot.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "frames/frame_trials.h"

namespace dtmf::bench {

struct TrialCounts {
  std::uint64_t frames = 0;  // sent
  std::uint64_t success = 0;
  std::uint64_t missed = 0;      // never accepted with the right bits
  std::uint64_t duplicated = 0;  // accepted with the right bits more than once
  std::uint64_t wrong_accepts = 0;
  std::uint64_t check_failed = 0;  // heard but failing the check (NACKed by a robot)

  TrialCounts& operator+=(const TrialCounts& o);
};

// Turns one slot of clean audio into what the microphone records (appended to `heard`).
using Channel = std::function<void(std::span<const float> clean, std::vector<float>& heard)>;

struct StreamOptions {
  std::size_t frames = 500;
  std::uint64_t seed = 1;            // frame contents
  std::size_t block_samples = 1024;  // receiver feed size
  // Slots of the channel alone (noise, whines) before the first frame: a robot listens long
  // before anyone speaks to it, so steady sounds are learnt by then. Anything accepted in
  // them is a wrong accept.
  std::size_t lead_in_slots = 0;
};

TrialCounts run_stream(FrameTrials& trials, const StreamOptions& options, const Channel& channel);

// Mean power of the frames' audio over its non-silent part (the chord), from `count`
// random frames: the "signal" of the SNR definition.
double mean_sound_power(FrameTrials& trials, std::size_t count, std::uint64_t seed);

}  // namespace dtmf::bench
