// Fast white Gaussian noise for the benchmarks: xoshiro256+ and the Box-Muller transform.
//
// The SNR sweep adds about 50 000 seconds of 48 kHz noise; std::normal_distribution over
// std::mt19937_64 costs several times more than decoding the audio. xoshiro256+ (Blackman
// and Vigna) gives 64 random bits in about a nanosecond, each draw yields two 24-bit
// uniforms, and Box-Muller turns a pair of uniforms into two independent N(0, 1) samples
// with one log, one sqrt and one sincos. Seeded through splitmix64, so a seed reproduces the
// same noise.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>

namespace dtmf::bench {

class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }

  // Adds N(0, sigma^2) to every sample of `out`.
  void add_to(std::span<float> out, float sigma) {
    std::size_t i = 0;
    for (; i + 1 < out.size(); i += 2) {
      float a, b;
      pair(a, b);
      out[i] += sigma * a;
      out[i + 1] += sigma * b;
    }
    if (i < out.size()) {
      float a, b;
      pair(a, b);
      out[i] += sigma * a;
    }
  }

 private:
  static std::uint64_t splitmix64(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

  std::uint64_t next() {
    const std::uint64_t result = s_[0] + s_[3];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  void pair(float& a, float& b) {
    const std::uint64_t r = next();
    constexpr float kScale = 1.0f / 16777216.0f;  // 2^-24
    // u1 in (0, 1] so that log(u1) is finite; u2 in [0, 1).
    const float u1 = (static_cast<float>(r >> 40) + 1.0f) * kScale;
    const float u2 = static_cast<float>((r >> 16) & 0xFFFFFF) * kScale;
    const float radius = std::sqrt(-2.0f * std::log(u1));
    const float angle = 2.0f * std::numbers::pi_v<float> * u2;
    a = radius * std::cos(angle);
    b = radius * std::sin(angle);
  }

  std::uint64_t s_[4];
};

}  // namespace dtmf::bench
