// Benchmarks' clock for "seconds of audio per CPU second": this thread's CPU time
// (CLOCK_THREAD_CPUTIME_ID), so a figure is one core's whatever else the machine does.
#pragma once

#include <ctime>

namespace dtmf::bench {

inline double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

}  // namespace dtmf::bench
