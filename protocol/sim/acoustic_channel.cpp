#include "sim/acoustic_channel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/clock_drift.h"
#include "sim/fft_convolver.h"
#include "sim/real_fft.h"
#include "units/decibels.h"

namespace dtmf::sim {

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
      const double gain = units::amplitude_ratio_from_db(-kAirAbsorptionDbPerMPerHz2 * f * f * distance_m);
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

void check_distance(double distance_m) {
  if (!std::isfinite(distance_m) || distance_m <= 0) {
    throw std::invalid_argument("transmitter distance must be a positive number of metres, got " +
                                std::to_string(distance_m));
  }
}

}  // namespace

double channel_loss_db(double frequency_hz, double distance_m) {
  return units::db_from_amplitude_ratio(distance_m) +
         kAirAbsorptionDbPerMPerHz2 * frequency_hz * frequency_hz * distance_m;
}

struct AcousticChannel::Transmitter {
  float gain;
  bool free_field;
  std::vector<float> taps;  // free field: absorption
  std::vector<float> fifo;  // free field: FIR history + propagation delay + pending input
  std::size_t read = 0;     // first sample of the next FIR window
  std::unique_ptr<MovingDelay> motion;
  std::unique_ptr<FftConvolver> convolver;  // room response and device responses, if any
  std::size_t delay_samples = 0;
  std::size_t response_samples = 0;
  double max_motion_delay_s = 0;
};

AcousticChannel::AcousticChannel(int sample_rate_hz, ChannelConfig config)
    : AcousticChannel(
          sample_rate_hz, config,
          config.room.enabled() ? std::make_shared<const RoomModel>(config.room, sample_rate_hz) : nullptr) {}

AcousticChannel::AcousticChannel(int sample_rate_hz, ChannelConfig config, std::shared_ptr<const RoomModel> room)
    : sample_rate_hz_(sample_rate_hz),
      config_(std::move(config)),
      room_(std::move(room)),
      noise_(config_.noise, sample_rate_hz, config_.seed),
      whines_(config_.whines, sample_rate_hz, config_.seed) {
  if (config_.reverb.rt60_s > 0 && room_) {
    throw std::invalid_argument(
        "a room already reverberates: give either a room or the diffuse reverberator's RT60, not both");
  }
  if (config_.reverb.rt60_s > 0) reverb_ = std::make_unique<SchroederReverb>(config_.reverb, sample_rate_hz);
  if (config_.clock_offset_ppm != 0) drift_ = std::make_unique<ClockDrift>(config_.clock_offset_ppm);
  if (!config_.speaker_response.flat()) speaker_fir_ = response_fir(config_.speaker_response, sample_rate_hz);
  if (!config_.mic_response.flat()) mic_fir_ = response_fir(config_.mic_response, sample_rate_hz);
}

AcousticChannel::~AcousticChannel() = default;

std::size_t AcousticChannel::add_transmitter(double distance_m, bool moves) {
  check_distance(distance_m);
  if (!room_) return add_path({distance_m, nullptr, 1, moves});
  if (room_->kind() == RoomModel::Kind::Measured)
    return add_path({distance_m, room_->measured_at(distance_m), 1 / distance_m, moves});
  return add_transmitter_at(room_->speaker_at_distance(distance_m), moves);
}

std::size_t AcousticChannel::add_transmitter_at(const Point3& speaker, bool moves) {
  if (!room_ || room_->kind() != RoomModel::Kind::ImageSource) {
    throw std::invalid_argument(
        "a loudspeaker position needs an image-source room (a shoebox); give a distance otherwise");
  }
  const Point3 mic = room_->microphone();
  return add_path({distance_m(speaker, mic), room_->between(speaker, mic), 1, moves});
}

std::size_t AcousticChannel::add_path(const PathSpec& path) {
  check_distance(path.distance_m);
  auto tx = std::make_unique<Transmitter>();
  tx->free_field = !path.response;
  const bool moving = path.moves && config_.motion.speed_mps != 0;
  const double samples_per_m = sample_rate_hz_ / kSpeedOfSoundMps;
  if (tx->free_field) {
    tx->gain = static_cast<float>(1.0 / path.distance_m);
    tx->taps = absorption_fir(path.distance_m, sample_rate_hz_);
    // Standing: the whole delay here. Moving: the part every position shares, leaving the
    // moving delay line at least its look-ahead (it supplies the rest, fractionally).
    const double fixed = moving ? std::floor(config_.motion.min_distance_m * samples_per_m) - kMovingDelayHalfTaps
                                : std::round(path.distance_m * samples_per_m);
    tx->delay_samples = static_cast<std::size_t>(std::max(fixed, 0.0));
    // The FIR's own delay of kFirHalf samples is part of the propagation delay where possible.
    const auto padding = std::max(tx->delay_samples, static_cast<std::size_t>(kFirHalf)) + kFirHalf;
    tx->fifo.assign(padding, 0.0f);
    if (moving) {
      tx->motion = std::make_unique<MovingDelay>(
          config_.motion, path.distance_m, static_cast<double>(std::max<std::size_t>(tx->delay_samples, kFirHalf)),
          sample_rate_hz_);
    }
  } else {
    tx->gain = static_cast<float>(path.gain);
    if (moving) {
      // A room's response is that of the starting position; the motion moves all of it.
      tx->motion = std::make_unique<MovingDelay>(config_.motion, path.distance_m,
                                                 config_.motion.min_distance_m * samples_per_m - kMovingDelayHalfTaps,
                                                 sample_rate_hz_);
    }
  }
  if (moving)
    tx->max_motion_delay_s = (config_.motion.max_distance_m - config_.motion.min_distance_m) / kSpeedOfSoundMps;
  // One convolution for the loudspeaker, the room and the microphone together.
  std::vector<float> response = path.response ? *path.response : std::vector<float>{};
  if (!speaker_fir_.empty()) response = response.empty() ? speaker_fir_ : convolve(speaker_fir_, response);
  if (!mic_fir_.empty()) response = response.empty() ? mic_fir_ : convolve(response, mic_fir_);
  if (!response.empty()) {
    tx->response_samples = response.size();
    tx->convolver = std::make_unique<FftConvolver>(response);
  }
  transmitters_.push_back(std::move(tx));
  return transmitters_.size() - 1;
}

double AcousticChannel::ring_out_s() const {
  double longest = 0;
  for (const auto& tx : transmitters_) {
    longest =
        std::max(longest, static_cast<double>(tx->delay_samples + tx->response_samples + kFirTaps) / sample_rate_hz_ +
                              tx->max_motion_delay_s);
  }
  return longest;
}

void AcousticChannel::process(std::span<const float> block, std::vector<float>& out) {
  const std::span<const float> blocks[1] = {block};
  process(blocks, out);
}

void AcousticChannel::process(std::span<const std::span<const float>> blocks, std::vector<float>& out) {
  if (blocks.size() != transmitters_.size()) {
    throw std::invalid_argument("process() needs one block per transmitter: " + std::to_string(transmitters_.size()) +
                                " transmitters, " + std::to_string(blocks.size()) + " blocks");
  }
  const std::size_t n = blocks.empty() ? 0 : blocks[0].size();
  mix_.assign(n, 0.0f);
  for (std::size_t t = 0; t < transmitters_.size(); ++t) {
    if (blocks[t].size() != n) throw std::invalid_argument("process() blocks differ in length");
    Transmitter& tx = *transmitters_[t];
    std::span<const float> in = blocks[t];
    if (tx.motion) {
      moved_.resize(n);
      tx.motion->process(in, moved_);
      in = moved_;
    }
    // What reaches the microphone before the responses (into scratch_ if they follow).
    std::span<float> target = mix_;
    if (tx.convolver) {
      scratch_.assign(n, 0.0f);
      target = scratch_;
    }
    if (tx.free_field) {
      tx.fifo.insert(tx.fifo.end(), in.begin(), in.end());
      const float* window = tx.fifo.data() + tx.read;
      for (std::size_t i = 0; i < n; ++i) {
        float acc = 0;
        for (int k = 0; k < kFirTaps; ++k)
          acc += tx.taps[static_cast<std::size_t>(k)] * window[i + static_cast<std::size_t>(k)];
        target[i] += tx.gain * acc;
      }
      tx.read += n;
      // Drop what no future window needs, in large steps so the copy stays cheap.
      if (tx.read > (1u << 16)) {
        tx.fifo.erase(tx.fifo.begin(), tx.fifo.begin() + static_cast<std::ptrdiff_t>(tx.read));
        tx.read = 0;
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) target[i] += tx.gain * in[i];
    }
    if (tx.convolver) tx.convolver->process_add(scratch_, mix_);
  }
  if (reverb_) reverb_->process(mix_);
  noise_.add_to(mix_);
  whines_.add_to(mix_);
  if (drift_)
    drift_->process(mix_, out);
  else
    out.insert(out.end(), mix_.begin(), mix_.end());
}

}  // namespace dtmf::sim
