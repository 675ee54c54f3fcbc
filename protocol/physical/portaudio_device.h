// Physical layer: sound cards and sound servers through PortAudio.
//
// Devices are found by index, by exact name, or by a unique case-insensitive part of the
// name ("pulse", "USB"); "default" is the host's default device. Streams are blocking,
// mono, float, with the buffer depth the caller asks for; a microphone is drained by a
// thread of its own (capture_thread.h), and its reader decodes at normal priority. With no device at all
// the error (NoAudioDevice) says how to get one; the program adds how it works with files instead. PortAudio is
// initialised while any device object lives.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "physical/audio_io.h"

namespace dtmf::physical {

// Thrown when no device can record (or play) at all.
class NoAudioDevice : public AudioError {
 public:
  using AudioError::AudioError;
};

// Device buffer depth, each way. 200 ms cured every underrun of a loaded 2-core machine,
// but a buffer delays every answer by its depth in each direction, and the fast profile's
// round trip (frame, ACK) must fit its 500 ms ACK timeout with room to spare: 50 ms keeps
// both profiles' end-to-end tests clean on these machines (docs/protocol.md §7).
inline constexpr double kDefaultAudioBufferMs = 50;
inline constexpr double kMinAudioBufferMs = 5, kMaxAudioBufferMs = 2000;

struct DeviceOptions {
  double buffer_ms = kDefaultAudioBufferMs;  // at least this deep, or the device's high latency if more
};

struct AudioDeviceInfo {
  int index;
  std::string name;
  std::string host_api;
  int max_input_channels;
  int max_output_channels;
  double default_sample_rate_hz;
};

// Every device PortAudio sees (may be empty). Throws AudioError if PortAudio cannot start.
std::vector<AudioDeviceInfo> list_audio_devices();

// One line per device, for a program to list them.
std::string format_device_list(const std::vector<AudioDeviceInfo>& devices);

enum class Direction { Input, Output };

// The device `spec` names (index, name, unique part of a name, or "default") that can
// record (Input) or play (Output). Throws AudioError naming the spec and the choices.
AudioDeviceInfo find_audio_device(const std::string& spec, Direction direction);

// Throws AudioError (NoAudioDevice when there is none at all), std::invalid_argument for a
// buffer depth outside kMinAudioBufferMs..kMaxAudioBufferMs.
std::unique_ptr<AudioSource> open_input_device(const std::string& spec, int sample_rate_hz,
                                               const DeviceOptions& options = {});
std::unique_ptr<AudioSink> open_output_device(const std::string& spec, int sample_rate_hz,
                                              const DeviceOptions& options = {});

}  // namespace dtmf::physical
