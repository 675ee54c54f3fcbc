#include "sim/measured_rir.h"

#include <samplerate.h>
#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "physical/audio_io.h"
#include "sim/number_text.h"

namespace dtmf::sim {

namespace {

constexpr double kDirectWithinOfLoudest = 0.5;  // -6 dB
constexpr double kDirectPeakSearchS = 0.001;    // the direct sound's peak lies within 1 ms of its onset
constexpr double kFadeOutS = 0.01;
// The direct sound's energy is taken over kRirDirectBeforeS..kRirDirectAfterS around its peak:
// a measured "impulse" is smeared over a few samples by the source (a clap, a loudspeaker)
// and the microphone.

std::vector<float> read_channel_zero(const std::string& path, int& rate_hz, int& channels) {
  SF_INFO info{};
  SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
  if (!file) {
    throw physical::AudioError("cannot read the room impulse response '" + path + "': " + sf_strerror(nullptr) +
                               " (give a WAV, FLAC or AIFF file, e.g. one of bench/rirs/)");
  }
  rate_hz = info.samplerate;
  channels = info.channels;
  if (info.frames > static_cast<sf_count_t>(kRirMaxLengthS * info.samplerate)) {
    sf_close(file);
    throw std::invalid_argument("the room impulse response '" + path + "' is " +
                                number_text(static_cast<double>(info.frames) / info.samplerate) +
                                " s long: a room's response dies away within a few seconds; is it a recording?");
  }
  std::vector<float> interleaved(static_cast<std::size_t>(info.frames) * static_cast<std::size_t>(channels));
  const sf_count_t got = sf_readf_float(file, interleaved.data(), info.frames);
  sf_close(file);
  std::vector<float> mono(static_cast<std::size_t>(std::max<sf_count_t>(got, 0)));
  for (std::size_t i = 0; i < mono.size(); ++i) mono[i] = interleaved[i * static_cast<std::size_t>(channels)];
  return mono;
}

std::vector<float> resample(const std::vector<float>& in, int from_hz, int to_hz, const std::string& path) {
  if (from_hz == to_hz) return in;
  const double ratio = static_cast<double>(to_hz) / from_hz;
  std::vector<float> out(static_cast<std::size_t>(std::ceil(static_cast<double>(in.size()) * ratio)) + 16);
  SRC_DATA data{};
  data.data_in = in.data();
  data.input_frames = static_cast<long>(in.size());
  data.data_out = out.data();
  data.output_frames = static_cast<long>(out.size());
  data.src_ratio = ratio;
  if (const int error = src_simple(&data, SRC_SINC_BEST_QUALITY, 1)) {
    throw physical::AudioError("cannot resample the room impulse response '" + path + "' from " +
                               std::to_string(from_hz) + " Hz: " + src_strerror(error));
  }
  out.resize(static_cast<std::size_t>(data.output_frames_gen));
  return out;
}

}  // namespace

MeasuredRir load_measured_rir(const std::string& path, int sample_rate_hz) {
  MeasuredRir rir;
  const std::vector<float> raw = read_channel_zero(path, rir.file_rate_hz, rir.file_channels);
  if (raw.empty()) {
    throw std::invalid_argument("the room impulse response '" + path + "' holds no samples: give a recorded response");
  }
  std::vector<float> h = resample(raw, rir.file_rate_hz, sample_rate_hz, path);
  float loudest = 0;
  for (float s : h) loudest = std::max(loudest, std::abs(s));
  if (!(loudest > 0) || !std::isfinite(loudest)) {
    throw std::invalid_argument("the room impulse response '" + path + "' is silent: give a recorded response");
  }

  const auto onset = static_cast<std::size_t>(
      std::find_if(h.begin(), h.end(), [&](float s) { return std::abs(s) >= kDirectWithinOfLoudest * loudest; }) -
      h.begin());
  std::size_t peak = onset;
  const auto search_end = std::min(h.size(), onset + static_cast<std::size_t>(kDirectPeakSearchS * sample_rate_hz));
  for (std::size_t i = onset; i < search_end; ++i) {
    if (std::abs(h[i]) > std::abs(h[peak])) peak = i;
  }
  const auto lead = static_cast<std::size_t>(std::lround(kRirLeadS * sample_rate_hz));
  const std::size_t start = peak > lead ? peak - lead : 0;
  // Scaled so that the direct sound carries the energy of a unit impulse: a transmitter's
  // samples are the direct sound's level at 1 m, as in free field. (Scaling its peak to 1
  // instead left the smeared direct sounds of these files 10-16 dB too loud.) A negative
  // direct peak (the microphone's polarity) becomes positive.
  double direct_energy = 0;
  const auto before = static_cast<std::size_t>(kRirDirectBeforeS * sample_rate_hz);
  const auto after = static_cast<std::size_t>(kRirDirectAfterS * sample_rate_hz);
  // Only what is kept counts: the window may reach back past the lead.
  for (std::size_t i = std::max(start, peak > before ? peak - before : 0); i < std::min(h.size(), peak + after); ++i) {
    direct_energy += static_cast<double>(h[i]) * h[i];
  }
  const float scale = static_cast<float>((h[peak] < 0 ? -1.0 : 1.0) / std::sqrt(direct_energy));
  rir.samples.assign(h.begin() + static_cast<std::ptrdiff_t>(start), h.end());
  for (float& s : rir.samples) s *= scale;
  rir.direct_index = peak - start;

  const auto fade =
      std::min(rir.samples.size() - rir.direct_index - 1, static_cast<std::size_t>(kFadeOutS * sample_rate_hz));
  for (std::size_t i = 0; i < fade; ++i) {
    const double t = static_cast<double>(i + 1) / static_cast<double>(fade + 1);  // 0 .. 1 towards the end
    rir.samples[rir.samples.size() - fade + i] *= static_cast<float>(0.5 + 0.5 * std::cos(std::numbers::pi * t));
  }
  return rir;
}

}  // namespace dtmf::sim
