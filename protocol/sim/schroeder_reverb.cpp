#include "sim/schroeder_reverb.h"

#include <cmath>

#include "units/decibels.h"

namespace dtmf::sim {

namespace {
// Schroeder's comb and all-pass delays, in ms (mutually prime in samples at usual rates).
constexpr double kCombMs[4] = {29.7, 37.1, 41.1, 43.7};
constexpr double kAllpassMs[2] = {5.0, 1.7};
constexpr double kAllpassGain = 0.7;
}  // namespace

SchroederReverb::SchroederReverb(const ReverbConfig& config, int sample_rate_hz)
    : wet_(static_cast<float>(config.wet)) {
  for (double ms : kCombMs) {
    const auto length = static_cast<std::size_t>(ms * sample_rate_hz / 1000.0);
    // Feedback that decays by 60 dB in rt60_s.
    const double g = units::amplitude_ratio_from_db(-60.0 * (ms / 1000.0) / config.rt60_s);
    combs_.push_back(Line{std::vector<float>(length, 0.0f), 0, static_cast<float>(g)});
  }
  for (double ms : kAllpassMs) {
    const auto length = static_cast<std::size_t>(ms * sample_rate_hz / 1000.0);
    allpasses_.push_back(Line{std::vector<float>(length, 0.0f), 0, static_cast<float>(kAllpassGain)});
  }
}

void SchroederReverb::process(std::span<float> x) {
  for (float& sample : x) {
    float reverberant = 0;
    for (Line& comb : combs_) {
      const float delayed = comb.buffer[comb.pos];
      comb.buffer[comb.pos] = sample + comb.feedback * delayed;
      comb.pos = (comb.pos + 1) % comb.buffer.size();
      reverberant += delayed;
    }
    reverberant *= 0.25f;
    for (Line& ap : allpasses_) {
      const float delayed = ap.buffer[ap.pos];
      const float in = reverberant + ap.feedback * delayed;
      ap.buffer[ap.pos] = in;
      ap.pos = (ap.pos + 1) % ap.buffer.size();
      reverberant = delayed - ap.feedback * in;
    }
    sample += wet_ * reverberant;
  }
}

}  // namespace dtmf::sim
