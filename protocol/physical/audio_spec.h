// Physical layer: choosing an audio source or sink from one flag value.
//
//   wav:PATH        a recording to read, or a file to write what would be played
//   default         the host's default device (the PulseAudio "air" when PULSE_* point at it)
//   NAME or INDEX   a PortAudio device (list_audio_devices); a unique part of a name will do
#pragma once

#include <memory>
#include <string>

#include "physical/audio_io.h"
#include "physical/portaudio_device.h"

namespace dtmf::physical {

bool is_file_spec(const std::string& spec);

// Throws AudioError with what to do when the spec cannot be opened. For files,
// `min_file_rate_hz` refuses recordings too slow to carry the tones.
// `devices` applies to devices only.
std::unique_ptr<AudioSource> open_audio_source(const std::string& spec, int sample_rate_hz, int min_file_rate_hz,
                                               const DeviceOptions& devices = {});
std::unique_ptr<AudioSink> open_audio_sink(const std::string& spec, int sample_rate_hz,
                                           const DeviceOptions& devices = {});

}  // namespace dtmf::physical
