#include "physical/wav_file.h"

#include <samplerate.h>
#include <sndfile.h>

#include <algorithm>
#include <cstring>

namespace dtmf::physical {

struct WavFileSource::Handles {
  SNDFILE* file = nullptr;
  SRC_STATE* resampler = nullptr;
  std::vector<float> interleaved;  // one block as the file stores it
  std::vector<float> mono;         // the same block mixed down, awaiting resampling
  std::size_t mono_used = 0;
  bool file_done = false;
  bool resampler_done = false;
};

namespace {
constexpr std::size_t kBlockFrames = 4096;
}

WavFileSource::WavFileSource(const std::string& path, int sample_rate_hz, int min_file_rate_hz)
    : path_(path), sample_rate_hz_(sample_rate_hz), handles_(std::make_unique<Handles>()) {
  SF_INFO info{};
  handles_->file = sf_open(path.c_str(), SFM_READ, &info);
  if (!handles_->file) {
    throw AudioError("cannot read audio file '" + path + "': " + sf_strerror(nullptr) +
                     " (give a WAV, FLAC or AIFF recording)");
  }
  file_rate_hz_ = info.samplerate;
  file_channels_ = info.channels;
  if (min_file_rate_hz > 0 && file_rate_hz_ < min_file_rate_hz) {
    sf_close(handles_->file);
    handles_->file = nullptr;
    throw AudioError("audio file '" + path + "' is sampled at " + std::to_string(file_rate_hz_) +
                     " Hz, too slow to carry the link's tones: record at " + std::to_string(sample_rate_hz) +
                     " Hz (at least " + std::to_string(min_file_rate_hz) + " Hz)");
  }
  handles_->interleaved.resize(kBlockFrames * static_cast<std::size_t>(file_channels_));
  handles_->mono.reserve(kBlockFrames);
  if (file_rate_hz_ != sample_rate_hz_) {
    int error = 0;
    handles_->resampler = src_new(SRC_SINC_MEDIUM_QUALITY, 1, &error);
    if (!handles_->resampler) {
      sf_close(handles_->file);
      handles_->file = nullptr;
      throw AudioError(std::string("cannot resample '") + path + "': " + src_strerror(error));
    }
  }
}

WavFileSource::~WavFileSource() {
  if (handles_->resampler) src_delete(handles_->resampler);
  if (handles_->file) sf_close(handles_->file);
}

std::string WavFileSource::describe() const {
  return "wav:" + path_ + " (" + std::to_string(file_rate_hz_) + " Hz, " + std::to_string(file_channels_) + " channel" +
         (file_channels_ == 1 ? "" : "s") + ")";
}

std::size_t WavFileSource::read_mono(std::span<float> out) {
  const std::size_t frames_wanted = std::min(out.size(), kBlockFrames);
  const auto channels = static_cast<std::size_t>(file_channels_);
  // A mono file needs no mixing: read straight into `out` (the mix loop cost the robot a tenth
  // of its time on a recording of noise).
  if (channels == 1) {
    const sf_count_t got = sf_readf_float(handles_->file, out.data(), static_cast<sf_count_t>(frames_wanted));
    return got > 0 ? static_cast<std::size_t>(got) : 0;
  }
  const sf_count_t got =
      sf_readf_float(handles_->file, handles_->interleaved.data(), static_cast<sf_count_t>(frames_wanted));
  if (got <= 0) return 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(got); ++i) {
    float sum = 0;
    for (std::size_t c = 0; c < channels; ++c) sum += handles_->interleaved[i * channels + c];
    out[i] = sum / static_cast<float>(channels);
  }
  return static_cast<std::size_t>(got);
}

std::size_t WavFileSource::read(std::span<float> out) {
  if (!handles_->file || out.empty()) return 0;
  if (!handles_->resampler) return read_mono(out);

  Handles& h = *handles_;
  std::size_t produced = 0;
  while (produced < out.size() && !h.resampler_done) {
    if (h.mono_used == h.mono.size() && !h.file_done) {
      h.mono.resize(kBlockFrames);
      h.mono.resize(read_mono(h.mono));
      h.mono_used = 0;
      h.file_done = h.mono.empty();
    }
    SRC_DATA data{};
    data.data_in = h.mono.data() + h.mono_used;
    data.input_frames = static_cast<long>(h.mono.size() - h.mono_used);
    data.data_out = out.data() + produced;
    data.output_frames = static_cast<long>(out.size() - produced);
    data.src_ratio = static_cast<double>(sample_rate_hz_) / file_rate_hz_;
    data.end_of_input = h.file_done ? 1 : 0;
    const int error = src_process(h.resampler, &data);
    if (error) throw AudioError("resampling '" + path_ + "' failed: " + src_strerror(error));
    h.mono_used += static_cast<std::size_t>(data.input_frames_used);
    produced += static_cast<std::size_t>(data.output_frames_gen);
    if (h.file_done && data.output_frames_gen == 0) h.resampler_done = true;
  }
  return produced;
}

WavFileSink::WavFileSink(const std::string& path, int sample_rate_hz) : path_(path), sample_rate_hz_(sample_rate_hz) {
  SF_INFO info{};
  info.samplerate = sample_rate_hz;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file) {
    throw AudioError("cannot write audio file '" + path + "': " + sf_strerror(nullptr) +
                     " (check that the folder exists and is writable)");
  }
  sf_command(file, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  file_ = file;
}

WavFileSink::~WavFileSink() { sf_close(static_cast<SNDFILE*>(file_)); }

void WavFileSink::write(std::span<const float> samples) {
  const sf_count_t written =
      sf_writef_float(static_cast<SNDFILE*>(file_), samples.data(), static_cast<sf_count_t>(samples.size()));
  if (written != static_cast<sf_count_t>(samples.size())) {
    throw AudioError("writing '" + path_ + "' failed: " + sf_strerror(static_cast<SNDFILE*>(file_)));
  }
}

void WavFileSink::drain() { sf_write_sync(static_cast<SNDFILE*>(file_)); }

RealTimeWavSink::RealTimeWavSink(const std::string& path, int sample_rate_hz) : WavFileSink(path, sample_rate_hz) {}

void RealTimeWavSink::write(std::span<const float> samples) {
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const auto due = static_cast<long long>(elapsed_s * sample_rate_hz());
  if (due > written_) {
    const std::vector<float> silence(static_cast<std::size_t>(due - written_), 0.0f);
    WavFileSink::write(silence);
    written_ = due;
  }
  WavFileSink::write(samples);
  written_ += static_cast<long long>(samples.size());
}

std::vector<float> read_audio_file(const std::string& path, int sample_rate_hz, int min_file_rate_hz) {
  WavFileSource source(path, sample_rate_hz, min_file_rate_hz);
  std::vector<float> samples;
  std::vector<float> block(kBlockFrames);
  while (const std::size_t got = source.read(block)) {
    samples.insert(samples.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(got));
  }
  return samples;
}

void write_wav_file(const std::string& path, std::span<const float> samples, int sample_rate_hz) {
  WavFileSink sink(path, sample_rate_hz);
  sink.write(samples);
  sink.drain();
}

}  // namespace dtmf::physical
