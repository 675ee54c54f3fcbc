// Signal layer: FFTW's wisdom kept on disk, so that a process plans each FFT size once per
// machine instead of once per start.
//
// A measured plan (FFTW_MEASURE) of the fast profile's 1920-point window runs in 1.65 µs
// where an estimated one takes 2.87 µs, but measuring costs about 0.5 s of CPU per size, and
// the fast receiver and reply ear need two sizes: 0.6-0.8 s at every start of dtmf-agent,
// dtmf-server or `dtmfctl decode`. With a wisdom file the first process measures and saves,
// and later ones import the plans and measure nothing (docs/benchmarks.md, start-up).
//
// The programs name the file once, before they build a receiver (use_fft_wisdom_file). The
// default, fft_wisdom_default_file(), is $DTMF_FFTW_WISDOM, else systemd's $CACHE_DIRECTORY,
// else $XDG_CACHE_HOME/dtmf-teleop, else ~/.cache/dtmf-teleop, each with /fftw-wisdom;
// DTMF_FFTW_WISDOM=none, or no variable at all, keeps plans in memory, as before. A file that cannot be read or written
// only costs the measuring time: wisdom is a cache, never a reason to fail.
#pragma once

#include <string>

namespace dtmf::signal {

// "" when no environment variable names a place.
std::string fft_wisdom_default_file();
// Imports the file's wisdom (if any) now, and saves new plans to it as they are measured.
// "" turns the file off. Thread-safe; call before building receivers for the gain.
void use_fft_wisdom_file(const std::string& path);

// For BinPower, under planner_mutex(): after measuring a plan FFTW did not know, save the
// wisdom (atomically: a temporary file renamed over the old one).
void fft_wisdom_learned();

}  // namespace dtmf::signal
