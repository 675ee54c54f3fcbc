// Physical layer: where samples come from and go to.
//
// Every source and sink carries mono float samples (full scale ±1.0) at one sample rate.
// Implementations: WAV files (wav_file.h), PortAudio devices (portaudio_device.h), and the
// simulated acoustic channel (acoustic_channel.h) for tests and demos.
#pragma once

#include <span>
#include <stdexcept>
#include <string>

namespace dtmf::physical {

// Anything that keeps audio from flowing; what() says what and what to do about it.
class AudioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AudioSource {
 public:
  virtual ~AudioSource() = default;
  // Fills up to out.size() samples; returns how many. 0 means the end of the stream.
  // A live device blocks until the samples have been captured.
  virtual std::size_t read(std::span<float> out) = 0;
  // Audio captured but not yet read: how far the reader is behind the microphone.
  virtual double queued_ms() const { return 0; }
  virtual int sample_rate_hz() const = 0;
  virtual std::string describe() const = 0;
};

class AudioSink {
 public:
  virtual ~AudioSink() = default;
  // Queues samples for playback; a live device blocks while its buffer is full.
  virtual void write(std::span<const float> samples) = 0;
  // Returns once everything written has been played (or stored).
  virtual void drain() = 0;
  virtual int sample_rate_hz() const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace dtmf::physical
