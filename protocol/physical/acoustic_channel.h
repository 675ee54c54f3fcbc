// Physical layer, part 5: a simulated room between loudspeakers and one microphone.
//
// Each transmitter (a loudspeaker) sits at a distance from the microphone. What it plays is
//   - delayed by distance / 343 m/s (whole samples),
//   - attenuated by spherical spreading, 1/distance (its samples are the level heard at 1 m),
//   - low-passed by air absorption, alpha(f) = 1.8e-9 * f^2 dB/m — a fit to ISO 9613-1 at
//     20 °C and 50 % relative humidity (0.12 dB/m at 8 kHz, 0.46 dB/m at 16 kHz), realised
//     as a short linear-phase FIR per transmitter.
// The transmitters are summed, optionally reverberated (a Schroeder room: four combs and two
// all-passes tuned to an RT60), noise is added (white, pink or a recording), and the sum is
// resampled with the microphone's clock offset in ppm (cubic interpolation).
//
// The channel streams: each process() call advances the room by one block of samples from
// every transmitter and appends what the microphone records (about as many samples; more or
// fewer with a clock offset). It is deterministic for a seed and runs many times faster than
// real time.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "physical/noise.h"

namespace dtmf::physical {

struct ReverbConfig {
  double rt60_s = 0;   // 0: no reverberation
  double wet = 0.3;    // level of the reverberant sound against the direct sound
};

struct ChannelConfig {
  NoiseConfig noise;
  ReverbConfig reverb;
  double clock_offset_ppm = 0;  // microphone clock against the loudspeakers' clock
  std::uint64_t seed = 1;
};

inline constexpr double kSpeedOfSoundMps = 343.0;
// Air absorption fit: alpha(f) = kAirAbsorptionDbPerMPerHz2 * f^2, in dB per metre.
inline constexpr double kAirAbsorptionDbPerMPerHz2 = 1.8e-9;

class AcousticChannel {
 public:
  AcousticChannel(int sample_rate_hz, ChannelConfig config);
  ~AcousticChannel();

  // Adds a loudspeaker `distance_m` from the microphone; returns its index for process().
  // Throws std::invalid_argument for a distance that is not positive and finite.
  std::size_t add_transmitter(double distance_m);

  // Advances the room by blocks[i].size() samples (all equal; one block per transmitter,
  // in add order) and appends the microphone's samples to `out`.
  void process(std::span<const std::span<const float>> blocks, std::vector<float>& out);

  // Convenience for one transmitter.
  void process(std::span<const float> block, std::vector<float>& out);

  int sample_rate_hz() const { return sample_rate_hz_; }

 private:
  struct Transmitter;
  struct Room;
  struct ClockDrift;

  int sample_rate_hz_;
  ChannelConfig config_;
  std::vector<std::unique_ptr<Transmitter>> transmitters_;
  std::unique_ptr<Room> room_;
  NoiseSource noise_;
  std::unique_ptr<ClockDrift> drift_;
  std::vector<float> mix_;
};

// Attenuation in dB that the channel applies at `frequency_hz` over `distance_m`
// (spreading plus absorption), for tests and docs.
double channel_loss_db(double frequency_hz, double distance_m);

}  // namespace dtmf::physical
