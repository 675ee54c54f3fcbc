// Physical layer: a simulated room between loudspeakers and one microphone.
//
// Each transmitter (a loudspeaker) reaches the microphone by one path:
//   - in free field (no room given): delayed by distance / 343 m/s (whole samples),
//     attenuated by spherical spreading, 1/distance (its samples are the level heard at
//     1 m), low-passed by air absorption, alpha(f) = 1.8e-9 * f^2 dB/m — a fit to ISO 9613-1
//     at 20 °C and 50 % relative humidity (0.12 dB/m at 8 kHz, 0.46 dB/m at 16 kHz) — as a
//     short linear-phase FIR;
//   - in a room (room_model.h): convolved with the room's impulse response from that
//     loudspeaker to the microphone (a measured one with its direct sound scaled by
//     1/distance and its reverberation as at 1 m, or an image-source one that holds delay,
//     spreading and absorption itself);
//   - through the loudspeaker's and the microphone's frequency responses
//     (frequency_response.h), folded into the same convolution (fft_convolver.h);
//   - and, for a transmitter that moves, through a delay and level that follow its
//     distance as it changes at a radial speed (radial_motion.h: Doppler).
// The paths are summed, optionally reverberated by the old diffuse reverberator
// (schroeder_reverb.h; not together with a room), noise is added (white, pink or a
// recording), then steady tones (whines.h), and the sum is resampled with the
// microphone's clock offset in ppm (clock_drift.h).
//
// The channel streams: each process() call advances the room by one block of samples from
// every transmitter and appends what the microphone records (as many samples; more or
// fewer with a clock offset). The output does not depend on how the input is split into
// blocks; it is deterministic for a seed and runs many times faster than real time, even
// through a room response of seconds.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sim/clock_drift.h"
#include "sim/frequency_response.h"
#include "sim/noise.h"
#include "sim/radial_motion.h"
#include "sim/room_model.h"
#include "sim/schroeder_reverb.h"
#include "sim/whines.h"

namespace dtmf::sim {

struct ChannelConfig {
  NoiseConfig noise;
  ReverbConfig reverb;                 // the diffuse reverberator; not with a room
  RoomConfig room;                     // a measured or image-source room; none: free field
  FrequencyResponse speaker_response;  // every transmitter's loudspeaker
  FrequencyResponse mic_response;
  std::vector<Whine> whines;    // at the microphone
  RadialMotion motion;          // for the transmitters added as moving
  double clock_offset_ppm = 0;  // microphone clock against the loudspeakers' clock
  std::uint64_t seed = 1;       // noise and whine phases
};

inline constexpr double kSpeedOfSoundMps = 343.0;
// Air absorption fit: alpha(f) = kAirAbsorptionDbPerMPerHz2 * f^2, in dB per metre.
inline constexpr double kAirAbsorptionDbPerMPerHz2 = 1.8e-9;

// One path from a loudspeaker to the microphone, for add_path().
struct PathSpec {
  double distance_m = 1;  // free field: delay, absorption and 1/d; a moving path starts here
  Response response;      // a room's impulse response; null: free field
  double gain = 1;        // with a response: 1/d for a measured room, 1 for an image-source one
  bool moves = true;      // follows config.motion (when its speed is not 0)
};

class AcousticChannel {
 public:
  // Prepares config.room (reading a file or calibrating a shoebox may take a second).
  // Throws std::invalid_argument / AudioError naming what is wrong in the configuration.
  AcousticChannel(int sample_rate_hz, ChannelConfig config);
  // With a room prepared once and shared (config.room is then ignored): a benchmark that
  // makes a channel per trial would otherwise read or calibrate the room every time.
  AcousticChannel(int sample_rate_hz, ChannelConfig config, std::shared_ptr<const RoomModel> room);
  ~AcousticChannel();

  // Adds a loudspeaker `distance_m` from the microphone; returns its index for process().
  // In an image-source room it stands where RoomModel::speaker_at_distance() puts it.
  // Throws std::invalid_argument for a distance that is not positive and finite.
  std::size_t add_transmitter(double distance_m, bool moves = true);
  // Image-source rooms only: a loudspeaker at a position (the microphone is the room's).
  std::size_t add_transmitter_at(const Point3& speaker, bool moves = true);
  // Any path, e.g. a response shared with another channel.
  std::size_t add_path(const PathSpec& path);

  // Advances the room by blocks[i].size() samples (all equal; one block per transmitter,
  // in add order) and appends the microphone's samples to `out`.
  void process(std::span<const std::span<const float>> blocks, std::vector<float>& out);

  // Convenience for one transmitter.
  void process(std::span<const float> block, std::vector<float>& out);

  int sample_rate_hz() const { return sample_rate_hz_; }
  // The room, if any (for its description and RT60).
  const RoomModel* room() const { return room_.get(); }
  // How long after its input stops the slowest path still sounds, seconds.
  double ring_out_s() const;

 private:
  struct Transmitter;

  int sample_rate_hz_;
  ChannelConfig config_;
  std::shared_ptr<const RoomModel> room_;
  std::vector<float> speaker_fir_, mic_fir_;
  std::vector<std::unique_ptr<Transmitter>> transmitters_;
  std::unique_ptr<SchroederReverb> reverb_;
  NoiseSource noise_;
  WhineSource whines_;
  std::unique_ptr<ClockDrift> drift_;
  std::vector<float> mix_, scratch_, moved_;
};

// Attenuation in dB that the free-field channel applies at `frequency_hz` over
// `distance_m` (spreading plus absorption), for tests and docs.
double channel_loss_db(double frequency_hz, double distance_m);

}  // namespace dtmf::sim
