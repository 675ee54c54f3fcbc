#include "sim/noise.h"

#include <cmath>

#include "physical/wav_file.h"
#include "units/decibels.h"

namespace dtmf::sim {

namespace {

// Paul Kellet's economy pink filter: three one-pole branches plus a direct term.
constexpr double kPole[3] = {0.99765, 0.96300, 0.57000};
constexpr double kGain[3] = {0.0990460, 0.2965164, 1.0526913};
constexpr double kDirect = 0.1848;

// The filter's output RMS for unit white input, from the branches' (co)variances
// g_i g_j / (1 - a_i a_j) and each branch's covariance g_i with the direct term.
double pink_rms() {
  double variance = kDirect * kDirect;
  for (int i = 0; i < 3; ++i) {
    variance += 2 * kDirect * kGain[i];
    for (int j = 0; j < 3; ++j) variance += kGain[i] * kGain[j] / (1 - kPole[i] * kPole[j]);
  }
  return std::sqrt(variance);
}

}  // namespace

NoiseConfig parse_noise(const std::string& text, double level_dbfs) {
  NoiseConfig config;
  config.level_dbfs = level_dbfs;
  if (text.empty() || text == "none")
    config.kind = NoiseKind::None;
  else if (text == "white")
    config.kind = NoiseKind::White;
  else if (text == "pink")
    config.kind = NoiseKind::Pink;
  else {
    config.kind = NoiseKind::File;
    config.file = text;
  }
  return config;
}

NoiseSource::NoiseSource(const NoiseConfig& config, int sample_rate_hz, std::uint64_t seed)
    : config_(config), rng_(seed) {
  scale_ = static_cast<float>(units::amplitude_ratio_from_db(config.level_dbfs));
  pink_scale_ = scale_ / pink_rms();
  if (config.kind == NoiseKind::File) {
    file_ = physical::read_audio_file(config.file, sample_rate_hz);
    double power = 0;
    for (float s : file_) power += static_cast<double>(s) * s;
    const double rms = file_.empty() ? 0.0 : std::sqrt(power / static_cast<double>(file_.size()));
    if (rms <= 0) throw physical::AudioError("noise file '" + config.file + "' is silent or empty");
    for (float& s : file_) s = static_cast<float>(s / rms);
    file_pos_ = std::uniform_int_distribution<std::size_t>(0, file_.size() - 1)(rng_);
  }
}

void NoiseSource::add_to(std::span<float> out) {
  switch (config_.kind) {
    case NoiseKind::None:
      return;
    case NoiseKind::White:
      for (float& s : out) s += scale_ * gauss_(rng_);
      return;
    case NoiseKind::Pink:
      for (float& s : out) {
        const double white = gauss_(rng_);
        b0_ = kPole[0] * b0_ + white * kGain[0];
        b1_ = kPole[1] * b1_ + white * kGain[1];
        b2_ = kPole[2] * b2_ + white * kGain[2];
        s += static_cast<float>(pink_scale_ * (b0_ + b1_ + b2_ + white * kDirect));
      }
      return;
    case NoiseKind::File:
      for (float& s : out) {
        s += scale_ * file_[file_pos_];
        if (++file_pos_ == file_.size()) file_pos_ = 0;
      }
      return;
  }
}

}  // namespace dtmf::sim
