#include "physical/portaudio_device.h"

#include <alsa/asoundlib.h>
#include <jack/jack.h>
#include <portaudio.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "physical/capture_thread.h"

namespace dtmf::physical {

namespace {

// PortAudio's own defaults (8.7 ms low, 35 ms high on PulseAudio) underran or overran
// whenever a loaded 2-core machine kept a thread off the CPU longer; DeviceOptions carries
// the depth the program chose (portaudio_device.h).
double buffer_s(const DeviceOptions& options) {
  if (!(options.buffer_ms >= kMinAudioBufferMs && options.buffer_ms <= kMaxAudioBufferMs)) {
    throw std::invalid_argument("audio buffer depth " + std::to_string(options.buffer_ms) + " ms is out of range " +
                                std::to_string(static_cast<int>(kMinAudioBufferMs)) + " to " +
                                std::to_string(static_cast<int>(kMaxAudioBufferMs)) + " ms");
  }
  return options.buffer_ms / 1000.0;
}

// PortAudio probes every ALSA and JACK device it can think of, and both libraries print
// each failed probe to stderr (hundreds of lines on a machine without a sound card). What
// matters reaches the user through PortAudio's error codes and the messages below.
void ignore_alsa_error(const char*, int, const char*, int, const char*, ...) {}

void silence_alsa_and_jack_probes() {
  static std::once_flag once;
  std::call_once(once, [] {
    snd_lib_error_set_handler(ignore_alsa_error);
    jack_set_error_function([](const char*) {});
    jack_set_info_function([](const char*) {});
  });
}

// Pa_Initialize / Pa_Terminate are reference counted by PortAudio itself; this keeps the
// calls paired and the error text clear.
class PortAudioSession {
 public:
  PortAudioSession() {
    silence_alsa_and_jack_probes();
    const PaError error = Pa_Initialize();
    if (error != paNoError) {
      throw AudioError(std::string("cannot start PortAudio: ") + Pa_GetErrorText(error));
    }
  }
  ~PortAudioSession() { Pa_Terminate(); }
  PortAudioSession(const PortAudioSession&) = delete;
  PortAudioSession& operator=(const PortAudioSession&) = delete;
};

const char* kNoDevice = "no audio device found: connect a sound card or start a sound server (PulseAudio, PipeWire)";

// kNoDevice, naming the sound server PulseAudio's own variable points at, when there is one.
std::string no_device_message(const char* what) {
  std::string message = std::string(kNoDevice) + " (no " + what + " device";
  if (const char* server = std::getenv("PULSE_SERVER")) {
    message += "; PulseAudio server " + std::string(server) + " did not answer";
  }
  return message + ")";
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::vector<AudioDeviceInfo> devices_now() {
  std::vector<AudioDeviceInfo> devices;
  const int count = Pa_GetDeviceCount();
  for (int i = 0; i < count; ++i) {
    const PaDeviceInfo* info = Pa_GetDeviceInfo(i);
    if (!info) continue;
    const PaHostApiInfo* api = Pa_GetHostApiInfo(info->hostApi);
    devices.push_back(AudioDeviceInfo{i, info->name ? info->name : "", api ? api->name : "", info->maxInputChannels,
                                      info->maxOutputChannels, info->defaultSampleRate});
  }
  return devices;
}

bool usable(const AudioDeviceInfo& device, Direction direction) {
  return direction == Direction::Input ? device.max_input_channels > 0 : device.max_output_channels > 0;
}

AudioDeviceInfo find_in(const std::vector<AudioDeviceInfo>& all, const std::string& spec, Direction direction) {
  const char* what = direction == Direction::Input ? "input" : "output";
  std::vector<AudioDeviceInfo> devices;
  std::copy_if(all.begin(), all.end(), std::back_inserter(devices),
               [&](const AudioDeviceInfo& d) { return usable(d, direction); });
  if (devices.empty()) throw NoAudioDevice(no_device_message(what));

  if (spec.empty() || spec == "default") {
    const int index = direction == Direction::Input ? Pa_GetDefaultInputDevice() : Pa_GetDefaultOutputDevice();
    for (const auto& d : devices)
      if (d.index == index) return d;
    return devices.front();
  }
  const bool numeric = std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); });
  if (numeric) {
    const int index = std::stoi(spec);
    for (const auto& d : devices)
      if (d.index == index) return d;
  }
  for (const auto& d : devices)
    if (d.name == spec) return d;
  std::vector<AudioDeviceInfo> partial;
  for (const auto& d : devices) {
    if (lower(d.name).find(lower(spec)) != std::string::npos) partial.push_back(d);
  }
  if (partial.size() == 1) return partial.front();
  const std::string problem = partial.empty() ? "matches no " : "matches several ";
  throw AudioError("audio device '" + spec + "' " + problem + what + " device; choose one of:\n" +
                   format_device_list(partial.empty() ? devices : partial));
}

class PortAudioStream {
 public:
  PortAudioStream(const std::string& spec, Direction direction, int sample_rate_hz, const DeviceOptions& options)
      : device_(find_in(devices_now(), spec, direction)), sample_rate_hz_(sample_rate_hz) {
    PaStreamParameters params{};
    params.device = device_.index;
    params.channelCount = 1;
    params.sampleFormat = paFloat32;
    const PaDeviceInfo* info = Pa_GetDeviceInfo(device_.index);
    // A buffer no shallower than asked for, or the device's high latency if more: a busy
    // machine then neither drops recorded samples nor plays gaps into a chord.
    params.suggestedLatency =
        std::max(buffer_s(options),
                 direction == Direction::Input ? info->defaultHighInputLatency : info->defaultHighOutputLatency);
    const PaError error = Pa_OpenStream(&stream_, direction == Direction::Input ? &params : nullptr,
                                        direction == Direction::Output ? &params : nullptr, sample_rate_hz,
                                        paFramesPerBufferUnspecified, paClipOff, nullptr, nullptr);
    if (error != paNoError) {
      throw AudioError("cannot open audio device " + std::to_string(device_.index) + " '" + device_.name + "' at " +
                       std::to_string(sample_rate_hz) + " Hz mono: " + Pa_GetErrorText(error) +
                       " (list the devices for the rates and channels each takes)");
    }
    const PaError started = Pa_StartStream(stream_);
    if (started != paNoError) {
      Pa_CloseStream(stream_);
      throw AudioError("cannot start audio device '" + device_.name + "': " + Pa_GetErrorText(started));
    }
  }
  ~PortAudioStream() {
    Pa_StopStream(stream_);
    Pa_CloseStream(stream_);
  }
  PortAudioStream(const PortAudioStream&) = delete;
  PortAudioStream& operator=(const PortAudioStream&) = delete;

  std::string describe() const {
    return "device " + std::to_string(device_.index) + " '" + device_.name + "' (" + device_.host_api + ")";
  }

  PortAudioSession session_;  // declared first: outlives the stream
  AudioDeviceInfo device_;
  int sample_rate_hz_;
  PaStream* stream_ = nullptr;
};

class PortAudioSource : public AudioSource {
 public:
  PortAudioSource(const std::string& spec, int rate, const DeviceOptions& options)
      : stream_(spec, Direction::Input, rate, options) {}
  double queued_ms() const override {
    const long frames = Pa_GetStreamReadAvailable(stream_.stream_);
    return frames > 0 ? 1000.0 * static_cast<double>(frames) / stream_.sample_rate_hz_ : 0.0;
  }
  // PortAudio's own wait polls the PulseAudio plugin, and under load the plugin said
  // "readable" while ALSA had no frame to give: PortAudio then polled in a loop at full CPU
  // (bench/e2e/fleet_load.sh, 20 agents: two readers at 94 %, gdb in Pa_ReadStream's poll).
  // So PortAudio is asked only for frames already captured, and the waiting is done here.
  std::size_t read(std::span<float> out) override {
    std::size_t done = 0;
    auto last_frame = std::chrono::steady_clock::now();
    while (done < out.size()) {
      const long available = Pa_GetStreamReadAvailable(stream_.stream_);
      if (available < 0) fail(static_cast<PaError>(available));
      if (available == 0) {
        if (std::chrono::steady_clock::now() - last_frame > kDeviceSilentLimit) {
          throw AudioError("recording from " + stream_.describe() + " delivered no sample for " +
                           std::to_string(kDeviceSilentLimit.count()) +
                           " ms: the device or the sound server has stalled (is it still running?)");
        }
        // Until the samples still missing could have been captured, as a blocking read waits.
        const auto missing = std::chrono::microseconds(
            static_cast<long long>(1e6 * static_cast<double>(out.size() - done) / stream_.sample_rate_hz_));
        std::this_thread::sleep_for(std::clamp(missing, kShortestLook, kLongestLook));
        continue;
      }
      const auto n = std::min(static_cast<std::size_t>(available), out.size() - done);
      const PaError error = Pa_ReadStream(stream_.stream_, out.data() + done, static_cast<unsigned long>(n));
      // An overflow lost samples to a busy machine; the stream itself goes on.
      if (error == paInputOverflowed && ++overflows_ % 100 == 1) {
        spdlog::warn("recording from {} lost samples ({} times so far): the machine is too busy to keep up",
                     stream_.describe(), overflows_);
      }
      if (error != paNoError && error != paInputOverflowed) fail(error);
      done += n;
      last_frame = std::chrono::steady_clock::now();
    }
    return out.size();
  }
  int sample_rate_hz() const override { return stream_.sample_rate_hz_; }
  std::string describe() const override { return stream_.describe(); }

 private:
  // A microphone delivers samples while it runs, silence included: none for this long is a
  // stall, not a quiet room (long enough for a loaded machine to set the stream up).
  static constexpr std::chrono::milliseconds kDeviceSilentLimit{10000};
  // Between looks at a device with nothing captured: the time the missing samples take, within
  // these bounds (a long block is still read as soon as part of it is there).
  static constexpr std::chrono::microseconds kShortestLook{1000}, kLongestLook{10000};

  [[noreturn]] void fail(PaError error) const {
    throw AudioError("recording from " + stream_.describe() + " failed: " + Pa_GetErrorText(error) +
                     " (is the device still connected?)");
  }

  PortAudioStream stream_;
  long overflows_ = 0;
};

class PortAudioSink : public AudioSink {
 public:
  PortAudioSink(const std::string& spec, int rate, const DeviceOptions& options)
      : stream_(spec, Direction::Output, rate, options) {}
  void write(std::span<const float> samples) override {
    const PaError error = Pa_WriteStream(stream_.stream_, samples.data(), static_cast<unsigned long>(samples.size()));
    if (error != paNoError && error != paOutputUnderflowed) {
      throw AudioError("playing to " + stream_.describe() + " failed: " + Pa_GetErrorText(error) +
                       " (is the device still connected?)");
    }
  }
  void drain() override {
    // Blocking streams have no drain call: wait out the device's output latency.
    Pa_Sleep(static_cast<long>(1000.0 * Pa_GetStreamInfo(stream_.stream_)->outputLatency) + 10);
  }
  int sample_rate_hz() const override { return stream_.sample_rate_hz_; }
  std::string describe() const override { return stream_.describe(); }

 private:
  PortAudioStream stream_;
};

}  // namespace

std::vector<AudioDeviceInfo> list_audio_devices() {
  PortAudioSession session;
  return devices_now();
}

std::string format_device_list(const std::vector<AudioDeviceInfo>& devices) {
  if (devices.empty()) return std::string(kNoDevice) + "\n";
  std::string text;
  for (const auto& d : devices) {
    char line[320];
    std::snprintf(line, sizeof line, "  %2d  %-40s %-6s in:%d out:%d  %.0f Hz\n", d.index, ("'" + d.name + "'").c_str(),
                  d.host_api.c_str(), d.max_input_channels, d.max_output_channels, d.default_sample_rate_hz);
    text += line;
  }
  return text;
}

AudioDeviceInfo find_audio_device(const std::string& spec, Direction direction) {
  PortAudioSession session;
  return find_in(devices_now(), spec, direction);
}

std::unique_ptr<AudioSource> open_input_device(const std::string& spec, int sample_rate_hz,
                                               const DeviceOptions& options) {
  return std::make_unique<CaptureThread>(std::make_unique<PortAudioSource>(spec, sample_rate_hz, options));
}

std::unique_ptr<AudioSink> open_output_device(const std::string& spec, int sample_rate_hz,
                                              const DeviceOptions& options) {
  return std::make_unique<PortAudioSink>(spec, sample_rate_hz, options);
}

}  // namespace dtmf::physical
