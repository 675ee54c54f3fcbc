#include "sim/whines.h"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "sim/number_text.h"
#include "units/decibels.h"

namespace dtmf::sim {

Whine parse_whine(const std::string& text) {
  const auto colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    std::size_t end_hz = 0, end_db = 0;
    const std::string hz = text.substr(0, colon), db = text.substr(colon + 1);
    Whine w{std::stod(hz, &end_hz), std::stod(db, &end_db)};
    if (end_hz != hz.size() || end_db != db.size()) throw std::invalid_argument("trailing text");
    return w;
  } catch (const std::exception&) {
    throw std::invalid_argument("whine '" + text + "' is not HZ:DBFS (a frequency and an RMS level, e.g. 9000:-45)");
  }
}

WhineSource::WhineSource(std::vector<Whine> whines, int sample_rate_hz, std::uint64_t seed)
    : whines_(std::move(whines)) {
  std::mt19937_64 rng(seed ^ 0x5748494e45ull);  // its own stream: adding a whine leaves the noise as it was
  std::uniform_real_distribution<double> phase(0.0, 1.0);
  for (const Whine& w : whines_) {
    if (!std::isfinite(w.frequency_hz) || w.frequency_hz <= 0 || w.frequency_hz >= sample_rate_hz / 2.0) {
      throw std::invalid_argument("whine at " + number_text(w.frequency_hz) + " Hz: give a frequency between 0 and " +
                                  std::to_string(sample_rate_hz / 2) + " Hz (half the sample rate)");
    }
    if (!std::isfinite(w.level_dbfs) || w.level_dbfs > 0) {
      throw std::invalid_argument("whine level " + number_text(w.level_dbfs) +
                                  " dBFS: give an RMS level at or below 0 dBFS (a full-scale sine is -3 dBFS)");
    }
    tones_.push_back(
        {w.frequency_hz / sample_rate_hz, std::sqrt(2.0) * units::amplitude_ratio_from_db(w.level_dbfs), phase(rng)});
  }
}

void WhineSource::add_to(std::span<float> out) {
  for (const Tone& t : tones_) {
    for (std::size_t i = 0; i < out.size(); ++i) {
      // The phase in cycles, reduced before it multiplies 2 pi: exact for streams of any length.
      const double cycles = std::fmod(
          t.cycles_per_sample * static_cast<double>(position_ + static_cast<long long>(i)) + t.phase_cycles, 1.0);
      out[i] += static_cast<float>(t.amplitude * std::sin(2 * std::numbers::pi * cycles));
    }
  }
  position_ += static_cast<long long>(out.size());
}

}  // namespace dtmf::sim
