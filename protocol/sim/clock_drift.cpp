#include "sim/clock_drift.h"

#include <samplerate.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "physical/audio_io.h"
#include "sim/number_text.h"

namespace dtmf::sim {

ClockDrift::ClockDrift(double ppm) : ratio_(1.0 + ppm * 1e-6) {
  if (!std::isfinite(ppm) || std::abs(ppm) > kMaxClockOffsetPpm) {
    throw std::invalid_argument("clock offset " + number_text(ppm) +
                                " ppm: give at most +-10000 ppm "
                                "(sound cards differ by up to about 100 ppm)");
  }
  int error = 0;
  state_ = src_new(SRC_SINC_MEDIUM_QUALITY, 1, &error);
  if (!state_)
    throw physical::AudioError(std::string("cannot start the clock-offset resampler: ") + src_strerror(error));
}

ClockDrift::~ClockDrift() { src_delete(static_cast<SRC_STATE*>(state_)); }

void ClockDrift::process(std::span<const float> air, std::vector<float>& out) {
  std::size_t used = 0;
  do {
    buffer_.resize(static_cast<std::size_t>(std::ceil(static_cast<double>(air.size() - used) * ratio_)) + 64);
    SRC_DATA data{};
    data.data_in = air.data() + used;
    data.input_frames = static_cast<long>(air.size() - used);
    data.data_out = buffer_.data();
    data.output_frames = static_cast<long>(buffer_.size());
    data.src_ratio = ratio_;
    data.end_of_input = 0;  // a stream: the air never ends
    if (const int error = src_process(static_cast<SRC_STATE*>(state_), &data)) {
      throw physical::AudioError(std::string("clock-offset resampling failed: ") + src_strerror(error));
    }
    used += static_cast<std::size_t>(data.input_frames_used);
    out.insert(out.end(), buffer_.begin(), buffer_.begin() + data.output_frames_gen);
    if (data.input_frames_used == 0 && data.output_frames_gen == 0) break;
  } while (used < air.size());
}

}  // namespace dtmf::sim
