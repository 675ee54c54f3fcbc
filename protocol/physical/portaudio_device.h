// Physical layer: sound cards and sound servers through PortAudio.
//
// Devices are found by index, by exact name, or by a unique case-insensitive part of the
// name ("pulse", "USB"); "default" is the host's default device. Streams are blocking,
// mono, float. With no device at all the error says how to get one: start a sound server,
// or use a file instead. PortAudio is initialised while any device object lives.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "physical/audio_io.h"

namespace dtmf::physical {

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

// One line per device, for --list-audio-devices.
std::string format_device_list(const std::vector<AudioDeviceInfo>& devices);

enum class Direction { Input, Output };

// The device `spec` names (index, name, unique part of a name, or "default") that can
// record (Input) or play (Output). Throws AudioError naming the spec and the choices.
AudioDeviceInfo find_audio_device(const std::string& spec, Direction direction);

std::unique_ptr<AudioSource> open_input_device(const std::string& spec, int sample_rate_hz);
std::unique_ptr<AudioSink> open_output_device(const std::string& spec, int sample_rate_hz);

}  // namespace dtmf::physical
