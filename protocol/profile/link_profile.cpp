#include "profile/link_profile.h"

#include <cmath>
#include <stdexcept>

namespace dtmf {

namespace {

LinkProfile make_seed_profile() {
  LinkProfile p;
  p.name = "seed";
  p.description = "the seed report's link: 0.8 s four-tone chords, about 17 bit/s";
  // 48 kHz: what the PulseAudio air and most USB microphones run at; 16 kHz tones
  // sit well below its 24 kHz Nyquist limit.
  p.sample_rate_hz = 48000;

  // Seed section 8: bands of 2500 Hz, 0000 = lowest, 1111 = highest tone of the band.
  p.tones.band_low_hz = {4500, 7500, 10500, 13500};
  p.tones.step_hz = 2500.0 / 15.0;
  p.tones.tones_per_band = 16;
  p.tones.ack_hz = {2500, 3500};   // seed section 9
  p.tones.nack_hz = {2000, 3000};
  p.tones.tone_amplitude = 0.2;    // four tones sum to at most 0.8 full scale
  p.tones.edge_ms = 5;             // long enough to keep clicks out of the tone bands

  p.timing.chord_ms = 800;         // seed section 9
  p.timing.gap_ms = 200;
  p.timing.ack_ms = 300;
  p.timing.ack_timeout_ms = 1500;
  p.timing.auto_retransmissions = 1;  // seed section 7, Fig. 8

  p.analysis.fft_size = 4096;       // seed section 8
  p.analysis.analyses_per_s = 20;

  p.robot_detector.bandpass_low_hz = 4000;   // seed section 8
  p.robot_detector.bandpass_high_hz = 17000;
  p.robot_detector.peak_count = 10;
  p.robot_detector.noise_gate_dbfs = -60;
  p.robot_detector.tone_tolerance_hz = 25;
  p.robot_detector.dominance_db = 8;  // spandsp's DTMF relative-peak test

  p.sender_detector.bandpass_low_hz = 1500;
  p.sender_detector.bandpass_high_hz = 4000;
  p.sender_detector.peak_count = 5;
  p.sender_detector.noise_gate_dbfs = -60;
  p.sender_detector.tone_tolerance_hz = 25;
  p.sender_detector.dominance_db = 8;

  p.debounce.min_detections = 2;   // seed section 8
  p.debounce.window_ms = 300;
  p.debounce.lockout_ms = 800;
  p.debounce.rearm_drop_db = 10;  // a reverberant tail must not pass a chord twice
  return p;
}

// The fast profile. Its sizes follow from two budgets, worked out in docs/protocol.md:
// energy (a 64-ary symbol needs Es/N0 of about 24 to be right 99.98 % of the time at
// -10 dB SNR, hence a 40 ms window for four tones at once) and compute (one 1920-point FFT
// per 10.25 ms hop is about 1.3 us here).
LinkProfile make_fast_profile() {
  LinkProfile p;
  p.name = "fast";
  p.description = "a whole command per 48-bit frame in 102.5 ms, named ACKs, CRC-16, about 250 bit/s";
  p.sample_rate_hz = 48000;
  p.frame_format = FrameFormat::Command48;

  BinLink& b = p.bins;
  b.window_samples = 1920;  // 40 ms; tones 25 Hz apart
  b.edge_samples = 24;      // 0.5 ms fades: the chord switch stays out of the other chord's bins
  b.hop_samples = 492;      // 10.25 ms; chord = 1920 + 2 * 24 + 492 = 2460 = 5 hops (51.25 ms)
  b.band_first_bin = {200, 268, 336, 404};  // 5000, 6700, 8400, 10100 Hz; 64 tones + 4 guard bins
  b.tones_per_band = 64;
  b.chords_per_frame = 2;
  b.tone_amplitude = 0.2;  // four tones sum to at most 0.8 full scale, as in the seed
  b.presence_db = 8;       // pure noise passes this in a band 1 window in 50 (best of 64 bins)
  b.dominance_db = 2;
  b.gone_db = 6;
  b.absent_bands = 1;
  b.chase_symbols = 2;
  b.lockout_hops = 7;       // docs/protocol.md §10, "Hearing a frame"
  b.cluster_gap_hops = 2.5;
  b.nack_settle_hops = 8;
  b.reply_window_samples = 768;  // 16 ms; reply tones 62.5 Hz apart
  b.reply_hop_samples = 192;     // 4 ms; a reply is 768 + 2 * 48 + 2 * 192 = 1248 samples (26 ms)
  b.reply_edge_samples = 48;
  b.reply_band_first_bin = {32, 50};  // 2000-2937.5 Hz and 3125-4062.5 Hz, below the chords
  b.reply_tones_per_band = 16;
  b.reply_amplitude = 0.4;
  b.reply_presence_db = 11;  // noise passes it in both bands once in 300 million windows
  b.reply_dominance_db = 6;  // speech's harmonics share a band at like levels

  // The shared fields, in the units the rest of the code base reads them in.
  const double ms_per_sample = 1000.0 / p.sample_rate_hz;
  p.tones.step_hz = static_cast<double>(p.sample_rate_hz) / b.window_samples;
  for (int i = 0; i < 4; ++i) p.tones.band_low_hz[i] = b.band_first_bin[i] * p.tones.step_hz;
  p.tones.tones_per_band = b.tones_per_band;
  p.tones.tone_amplitude = b.tone_amplitude;
  p.tones.edge_ms = b.edge_samples * ms_per_sample;
  p.timing.chord_ms = b.chord_samples() * ms_per_sample;
  p.timing.gap_ms = 0;
  p.timing.ack_ms = b.reply_samples() * ms_per_sample;
  p.timing.ack_timeout_ms = 500;  // an answer comes about 135 ms after the frame starts
  p.timing.auto_retransmissions = 2;
  p.analysis.fft_size = b.window_samples;
  p.analysis.analyses_per_s = static_cast<double>(p.sample_rate_hz) / b.hop_samples;
  return p;
}

}  // namespace

int LinkProfile::hop_samples() const {
  return static_cast<int>(std::lround(sample_rate_hz / analysis.analyses_per_s));
}

int LinkProfile::samples_for_ms(double ms) const {
  return static_cast<int>(std::lround(ms * sample_rate_hz / 1000.0));
}

int LinkProfile::min_recording_rate_hz() const {
  const double top_hz = tones.band_low_hz[3] + (tones.tones_per_band - 1) * tones.step_hz;
  return static_cast<int>(2 * top_hz) + 1;
}

const LinkProfile& seed_profile() {
  static const LinkProfile profile = make_seed_profile();
  return profile;
}

const LinkProfile& fast_profile() {
  static const LinkProfile profile = make_fast_profile();
  return profile;
}

const std::vector<const LinkProfile*>& all_profiles() {
  static const std::vector<const LinkProfile*> profiles = {&seed_profile(), &fast_profile()};
  return profiles;
}

std::string profile_names() {
  std::string names;
  for (const LinkProfile* p : all_profiles()) {
    if (!names.empty()) names += ", ";
    names += p->name;
  }
  return names;
}

const LinkProfile& profile_by_name(std::string_view name) {
  for (const LinkProfile* p : all_profiles()) {
    if (p->name == name) return *p;
  }
  throw std::invalid_argument("unknown link profile '" + std::string(name) +
                              "': choose one of " + profile_names());
}

}  // namespace dtmf
