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

  p.sender_detector.bandpass_low_hz = 1500;
  p.sender_detector.bandpass_high_hz = 4000;
  p.sender_detector.peak_count = 5;
  p.sender_detector.noise_gate_dbfs = -60;
  p.sender_detector.tone_tolerance_hz = 25;

  p.debounce.min_detections = 2;   // seed section 8
  p.debounce.window_ms = 300;
  p.debounce.lockout_ms = 800;
  p.debounce.rearm_drop_db = 10;  // a reverberant tail must not pass a chord twice
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

const std::vector<const LinkProfile*>& all_profiles() {
  static const std::vector<const LinkProfile*> profiles = {&seed_profile()};
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
