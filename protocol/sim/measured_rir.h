// Physical layer, rooms: a measured room impulse response (RIR) from a file.
//
// Any file libsndfile reads, at any rate. Only channel 0 is used: the channels of a
// stereo RIR were recorded by microphones a few centimetres apart, and their average
// would be a comb filter no single microphone hears. The response is resampled to the
// channel's rate with libsamplerate (best sinc), its leading silence is cut off up to
// kRirLeadS before the direct sound, it is scaled so that the direct sound (2.5 ms around
// its peak) carries the energy of a unit impulse, its peak positive (the level a
// transmitter's samples stand for, heard at 1 m: see acoustic_channel.h for how a
// transmitter's distance then scales it), and it fades out over its last 10 ms. The room's
// reverberation comes on top: 5-13 dB more power in 4.5-16 kHz than the free field for
// these three rooms, as a microphone in them hears.
//
// The direct sound is the first peak within 6 dB of the largest: in a measured room the
// direct sound is the loudest single arrival unless something blocks it, and taking the
// first of the near-loudest keeps a strong early reflection from being taken for it.
#pragma once

#include <string>
#include <vector>

namespace dtmf::sim {

inline constexpr double kRirLeadS = 0.00025;  // kept before the direct sound's peak (12 samples at 48 kHz)
inline constexpr double kRirMaxLengthS = 10;  // longer files are refused: recordings, not responses
// The direct sound: from 1 ms before its peak to 1.5 ms after; the rest is the room's.
inline constexpr double kRirDirectBeforeS = 0.001;
inline constexpr double kRirDirectAfterS = 0.0015;

struct MeasuredRir {
  std::vector<float> samples;  // at the rate asked for, the direct sound's peak (positive) at `direct_index`
  std::size_t direct_index = 0;
  int file_rate_hz = 0;
  int file_channels = 0;
};

// Throws AudioError for a file that cannot be read, std::invalid_argument for one that is
// empty, silent or too long; each message names the file and what to do.
MeasuredRir load_measured_rir(const std::string& path, int sample_rate_hz);

}  // namespace dtmf::sim
