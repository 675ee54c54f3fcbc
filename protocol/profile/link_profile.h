// Link profile: every timing and frequency parameter of the acoustic link in one value.
//
// Both sides must run the same profile. The `seed` profile carries the figures of the
// report this project implements (0.8 s chords, 4.5–16 kHz tone bands, 4096-point FFT at
// about 20 analyses per second, 2-of-0.3 s debouncing, 0.8 s lockout); where the report
// is silent the choice and its reason are in docs/protocol.md. Nothing else in the code
// base may hard-code these numbers: layers take the part of the profile they need.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace dtmf {

// The four-band tone plan of the command chords: band b carries nibble b of the 16-bit
// frame (most significant first), nibble value v sounds at band_low_hz[b] + v * step_hz.
struct TonePlan {
  std::array<double, 4> band_low_hz{};
  double step_hz = 0;
  int tones_per_band = 16;
  std::array<double, 2> ack_hz{};   // positive acknowledgement chord
  std::array<double, 2> nack_hz{};  // negative acknowledgement chord
  double tone_amplitude = 0;        // linear, per tone, full scale = 1.0
  double edge_ms = 0;               // raised-cosine fade in and out of every chord
};

// How long things sound and how long the sender waits.
struct LinkTiming {
  double chord_ms = 0;        // one command frame on air
  double gap_ms = 0;          // silence between two frames from the sender
  double ack_ms = 0;          // the robot's ACK / NACK chord
  double ack_timeout_ms = 0;  // from the start of a frame's chord until it counts as unanswered
  int auto_retransmissions = 0;  // retransmissions before the caller is asked
};

// Spectrum analysis shared by both sides.
struct AnalysisParams {
  int fft_size = 0;
  double analyses_per_s = 0;  // hop = sample_rate / analyses_per_s
};

// One side's peak detector: what it keeps of the spectrum and what counts as a tone.
struct DetectorParams {
  double bandpass_low_hz = 0;
  double bandpass_high_hz = 0;
  int peak_count = 0;           // the N loudest peaks considered
  double noise_gate_dbfs = 0;   // peaks below this (as a sine amplitude) are ignored
  double tone_tolerance_hz = 0; // how far a peak may sit from a plan tone and still match it
};

// When a detected chord becomes a frame.
struct DebounceParams {
  int min_detections = 0;   // detections of the same chord needed ...
  double window_ms = 0;     // ... within this time
  double lockout_ms = 0;    // after a pass, the same chord is ignored this long ...
  double rearm_drop_db = 0; // ... and until it has faded this far (or gone) in some window
};

struct LinkProfile {
  std::string name;
  std::string description;
  int sample_rate_hz = 0;
  TonePlan tones;
  LinkTiming timing;
  AnalysisParams analysis;
  DetectorParams robot_detector;   // hears command chords
  DetectorParams sender_detector;  // hears ACK / NACK chords
  DebounceParams debounce;

  int hop_samples() const;
  int samples_for_ms(double ms) const;
  // The slowest sample rate a recording may have and still carry the highest plan tone.
  int min_recording_rate_hz() const;
};

// The seed report's link.
const LinkProfile& seed_profile();

// Every profile this build knows, in the order `--profile` help lists them.
const std::vector<const LinkProfile*>& all_profiles();

// The profile called `name`; throws std::invalid_argument naming the known profiles.
const LinkProfile& profile_by_name(std::string_view name);

// "seed, fast" — for help texts and error messages.
std::string profile_names();

}  // namespace dtmf
