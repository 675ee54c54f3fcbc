// Physical layer: audio files through libsndfile.
//
// Reading accepts anything libsndfile reads (WAV, FLAC, AIFF, ... in any sample format),
// mixes channels down to mono and resamples to the rate asked for with libsamplerate; a
// file sampled too slowly to carry the link's tones is refused. Reading streams, so a long
// recording needs only a small buffer. Writing produces 16-bit PCM WAV.
#pragma once

#include <chrono>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "physical/audio_io.h"

namespace dtmf::physical {

class WavFileSource : public AudioSource {
 public:
  // Throws AudioError when the file cannot be read or its rate is below min_file_rate_hz.
  WavFileSource(const std::string& path, int sample_rate_hz, int min_file_rate_hz = 0);
  ~WavFileSource() override;

  std::size_t read(std::span<float> out) override;
  int sample_rate_hz() const override { return sample_rate_hz_; }
  std::string describe() const override;
  int file_rate_hz() const { return file_rate_hz_; }
  int file_channels() const { return file_channels_; }

 private:
  std::size_t read_mono(std::span<float> out);

  std::string path_;
  int sample_rate_hz_;
  int file_rate_hz_ = 0;
  int file_channels_ = 0;
  struct Handles;
  std::unique_ptr<Handles> handles_;
};

class WavFileSink : public AudioSink {
 public:
  WavFileSink(const std::string& path, int sample_rate_hz);
  ~WavFileSink() override;

  void write(std::span<const float> samples) override;
  void drain() override;
  int sample_rate_hz() const override { return sample_rate_hz_; }
  std::string describe() const override { return "wav:" + path_; }

 private:
  std::string path_;
  int sample_rate_hz_;
  void* file_;
};

// A file standing in for a loudspeaker: silence fills the wall-clock time between writes,
// so the file plays back as the sound would have been heard (a sender that writes its chords to a file).
class RealTimeWavSink : public WavFileSink {
 public:
  RealTimeWavSink(const std::string& path, int sample_rate_hz);
  void write(std::span<const float> samples) override;

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  long long written_ = 0;
};

// Whole-file helpers.
std::vector<float> read_audio_file(const std::string& path, int sample_rate_hz, int min_file_rate_hz = 0);
void write_wav_file(const std::string& path, std::span<const float> samples, int sample_rate_hz);

}  // namespace dtmf::physical
