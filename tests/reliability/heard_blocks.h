// Test support for the carrier sense: the microphone's blocks, fed at a steady level.
#pragma once

#include "reliability/carrier_sense.h"

namespace dtmf::test_support {

inline constexpr double kBlockMs = 10;

// `ms` of blocks at `level_dbfs` from `from_ms`; returns the end.
inline double hear_for(reliability::CarrierSense& sense, double from_ms, double ms, double level_dbfs) {
  double t = from_ms;
  for (; t < from_ms + ms; t += kBlockMs) sense.hear(level_dbfs, t + kBlockMs);
  return t;
}

}  // namespace dtmf::test_support
