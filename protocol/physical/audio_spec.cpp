#include "physical/audio_spec.h"

#include "physical/portaudio_device.h"
#include "physical/wav_file.h"

namespace dtmf::physical {

namespace {
constexpr const char* kFilePrefix = "wav:";
std::string file_of(const std::string& spec) { return spec.substr(std::char_traits<char>::length(kFilePrefix)); }
}  // namespace

bool is_file_spec(const std::string& spec) { return spec.rfind(kFilePrefix, 0) == 0; }

std::unique_ptr<AudioSource> open_audio_source(const std::string& spec, int sample_rate_hz, int min_file_rate_hz,
                                               const DeviceOptions& devices) {
  if (is_file_spec(spec)) return std::make_unique<WavFileSource>(file_of(spec), sample_rate_hz, min_file_rate_hz);
  return open_input_device(spec, sample_rate_hz, devices);
}

std::unique_ptr<AudioSink> open_audio_sink(const std::string& spec, int sample_rate_hz, const DeviceOptions& devices) {
  if (is_file_spec(spec)) return std::make_unique<WavFileSink>(file_of(spec), sample_rate_hz);
  return open_output_device(spec, sample_rate_hz, devices);
}

}  // namespace dtmf::physical
