#include "physical/acoustic_channel.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace dtmf::physical {

namespace {

constexpr int kFirHalf = 8;  // 17 taps: absorption below 20 m is a gentle low-pass
constexpr int kFirTaps = 2 * kFirHalf + 1;

// Linear-phase FIR whose response follows 10^(-alpha(f) * d / 20), by frequency sampling.
std::vector<float> absorption_fir(double distance_m, int sample_rate_hz) {
  constexpr int kGrid = 512;
  std::vector<float> taps(kFirTaps);
  double sum = 0;
  for (int n = -kFirHalf; n <= kFirHalf; ++n) {
    double h = 0;
    for (int k = 0; k < kGrid; ++k) {
      const double f = (k + 0.5) * sample_rate_hz / (2.0 * kGrid);
      const double gain = std::pow(10.0, -kAirAbsorptionDbPerMPerHz2 * f * f * distance_m / 20.0);
      h += gain * std::cos(std::numbers::pi * (k + 0.5) * n / kGrid);
    }
    h /= kGrid;
    // A Hann taper keeps the truncated response smooth.
    h *= 0.5 + 0.5 * std::cos(std::numbers::pi * n / (kFirHalf + 1));
    taps[static_cast<std::size_t>(n + kFirHalf)] = static_cast<float>(h);
    sum += h;
  }
  // Absorption is negligible at low frequencies: keep the DC gain at exactly 1.
  for (float& t : taps) t = static_cast<float>(t / sum);
  return taps;
}

// Schroeder's comb and all-pass delays, in ms (mutually prime in samples at usual rates).
constexpr double kCombMs[4] = {29.7, 37.1, 41.1, 43.7};
constexpr double kAllpassMs[2] = {5.0, 1.7};
constexpr double kAllpassGain = 0.7;

}  // namespace

double channel_loss_db(double frequency_hz, double distance_m) {
  return 20.0 * std::log10(distance_m) + kAirAbsorptionDbPerMPerHz2 * frequency_hz * frequency_hz * distance_m;
}

struct AcousticChannel::Transmitter {
  float gain;
  std::vector<float> taps;
  std::vector<float> fifo;  // FIR history + propagation delay + pending input
  std::size_t read = 0;     // first sample of the next FIR window
};

struct AcousticChannel::Room {
  struct Line {
    std::vector<float> buffer;
    std::size_t pos = 0;
    float feedback;
  };
  std::vector<Line> combs;
  std::vector<Line> allpasses;
  float wet;

  Room(const ReverbConfig& config, int sample_rate_hz) : wet(static_cast<float>(config.wet)) {
    for (double ms : kCombMs) {
      const auto length = static_cast<std::size_t>(ms * sample_rate_hz / 1000.0);
      // Feedback that decays by 60 dB in rt60_s.
      const double g = std::pow(10.0, -3.0 * (ms / 1000.0) / config.rt60_s);
      combs.push_back(Line{std::vector<float>(length, 0.0f), 0, static_cast<float>(g)});
    }
    for (double ms : kAllpassMs) {
      const auto length = static_cast<std::size_t>(ms * sample_rate_hz / 1000.0);
      allpasses.push_back(Line{std::vector<float>(length, 0.0f), 0, static_cast<float>(kAllpassGain)});
    }
  }

  void process(std::span<float> x) {
    for (float& sample : x) {
      float reverberant = 0;
      for (Line& comb : combs) {
        const float delayed = comb.buffer[comb.pos];
        comb.buffer[comb.pos] = sample + comb.feedback * delayed;
        comb.pos = (comb.pos + 1) % comb.buffer.size();
        reverberant += delayed;
      }
      reverberant *= 0.25f;
      for (Line& ap : allpasses) {
        const float delayed = ap.buffer[ap.pos];
        const float in = reverberant + ap.feedback * delayed;
        ap.buffer[ap.pos] = in;
        ap.pos = (ap.pos + 1) % ap.buffer.size();
        reverberant = delayed - ap.feedback * in;
      }
      sample += wet * reverberant;
    }
  }
};

struct AcousticChannel::ClockDrift {
  double step;                  // room samples per microphone sample
  double position = 1.0;        // next read position, relative to history[0]
  std::vector<float> history;   // room samples not yet fully consumed

  explicit ClockDrift(double ppm) : step(1.0 / (1.0 + ppm * 1e-6)), history(1, 0.0f) {}

  void process(std::span<const float> room, std::vector<float>& out) {
    history.insert(history.end(), room.begin(), room.end());
    // Cubic (Catmull-Rom) interpolation needs one sample before and two after.
    while (position + 2.0 < static_cast<double>(history.size())) {
      const auto i = static_cast<std::size_t>(position);
      const float t = static_cast<float>(position - static_cast<double>(i));
      const float y0 = history[i - 1], y1 = history[i], y2 = history[i + 1], y3 = history[i + 2];
      const float a = -0.5f * y0 + 1.5f * y1 - 1.5f * y2 + 0.5f * y3;
      const float b = y0 - 2.5f * y1 + 2.0f * y2 - 0.5f * y3;
      const float c = -0.5f * y0 + 0.5f * y2;
      out.push_back(((a * t + b) * t + c) * t + y1);
      position += step;
    }
    const auto consumed = static_cast<std::size_t>(position) - 1;
    history.erase(history.begin(), history.begin() + static_cast<std::ptrdiff_t>(consumed));
    position -= static_cast<double>(consumed);
  }
};

AcousticChannel::AcousticChannel(int sample_rate_hz, ChannelConfig config)
    : sample_rate_hz_(sample_rate_hz),
      config_(std::move(config)),
      noise_(config_.noise, sample_rate_hz, config_.seed) {
  if (config_.reverb.rt60_s > 0) room_ = std::make_unique<Room>(config_.reverb, sample_rate_hz);
  if (config_.clock_offset_ppm != 0) drift_ = std::make_unique<ClockDrift>(config_.clock_offset_ppm);
}

AcousticChannel::~AcousticChannel() = default;

std::size_t AcousticChannel::add_transmitter(double distance_m) {
  if (!std::isfinite(distance_m) || distance_m <= 0) {
    throw std::invalid_argument("transmitter distance must be a positive number of metres, got " +
                                std::to_string(distance_m));
  }
  auto tx = std::make_unique<Transmitter>();
  tx->gain = static_cast<float>(1.0 / distance_m);
  tx->taps = absorption_fir(distance_m, sample_rate_hz_);
  // The FIR's own delay of kFirHalf samples is part of the propagation delay where possible.
  const auto delay = static_cast<long>(std::lround(distance_m / kSpeedOfSoundMps * sample_rate_hz_));
  const auto padding = static_cast<std::size_t>(std::max(delay, static_cast<long>(kFirHalf)) + kFirHalf);
  tx->fifo.assign(padding, 0.0f);
  transmitters_.push_back(std::move(tx));
  return transmitters_.size() - 1;
}

void AcousticChannel::process(std::span<const float> block, std::vector<float>& out) {
  const std::span<const float> blocks[1] = {block};
  process(blocks, out);
}

void AcousticChannel::process(std::span<const std::span<const float>> blocks, std::vector<float>& out) {
  if (blocks.size() != transmitters_.size()) {
    throw std::invalid_argument("process() needs one block per transmitter: " +
                                std::to_string(transmitters_.size()) + " transmitters, " +
                                std::to_string(blocks.size()) + " blocks");
  }
  const std::size_t n = blocks.empty() ? 0 : blocks[0].size();
  mix_.assign(n, 0.0f);
  for (std::size_t t = 0; t < transmitters_.size(); ++t) {
    if (blocks[t].size() != n) throw std::invalid_argument("process() blocks differ in length");
    Transmitter& tx = *transmitters_[t];
    tx.fifo.insert(tx.fifo.end(), blocks[t].begin(), blocks[t].end());
    const float* window = tx.fifo.data() + tx.read;
    for (std::size_t i = 0; i < n; ++i) {
      float acc = 0;
      for (int k = 0; k < kFirTaps; ++k) acc += tx.taps[static_cast<std::size_t>(k)] * window[i + static_cast<std::size_t>(k)];
      mix_[i] += tx.gain * acc;
    }
    tx.read += n;
    // Drop what no future window needs, in large steps so the copy stays cheap.
    if (tx.read > (1u << 16)) {
      tx.fifo.erase(tx.fifo.begin(), tx.fifo.begin() + static_cast<std::ptrdiff_t>(tx.read));
      tx.read = 0;
    }
  }
  if (room_) room_->process(mix_);
  noise_.add_to(mix_);
  if (drift_) drift_->process(mix_, out);
  else out.insert(out.end(), mix_.begin(), mix_.end());
}

}  // namespace dtmf::physical
