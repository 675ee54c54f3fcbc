// Physical layer: noise for the simulated acoustic channel.
//
// White: Gaussian, flat to fs/2. Pink: white shaped by Paul Kellet's economy filter
// (-3 dB/octave within 0.5 dB above about 40 Hz at 48 kHz). File: any recording (speech, music),
// looped from a seeded starting point. Every generator is scaled to the RMS level asked
// for (dBFS, where a full-scale sine reads -3 dBFS RMS) and is deterministic for a seed.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace dtmf::sim {

enum class NoiseKind { None, White, Pink, File };

struct NoiseConfig {
  NoiseKind kind = NoiseKind::None;
  double level_dbfs = -60;  // RMS
  std::string file;         // for NoiseKind::File
};

// "none", "white", "pink" or a file path -> NoiseKind (a path means File).
NoiseConfig parse_noise(const std::string& text, double level_dbfs);

class NoiseSource {
 public:
  NoiseSource(const NoiseConfig& config, int sample_rate_hz, std::uint64_t seed);
  // Adds noise to every sample of `out`.
  void add_to(std::span<float> out);

 private:
  NoiseConfig config_;
  float scale_ = 0;
  double pink_scale_ = 0;
  std::mt19937_64 rng_;
  std::normal_distribution<float> gauss_{0.0f, 1.0f};
  double b0_ = 0, b1_ = 0, b2_ = 0;  // pink filter state
  std::vector<float> file_;          // normalised to RMS 1
  std::size_t file_pos_ = 0;
};

}  // namespace dtmf::sim
