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
  double dominance_db = 0;      // a band's tone must stand this far above its other plan tones
};

// When a detected chord becomes a frame.
struct DebounceParams {
  int min_detections = 0;   // detections of the same chord needed ...
  double window_ms = 0;     // ... within this time
  double lockout_ms = 0;    // after a pass, the same chord is ignored this long ...
  double rearm_drop_db = 0; // ... and until it has faded this far (or gone) in some window
};

// How a command travels. Word16: the seed's — RESET, mode and parameter words, one 16-bit
// CRC-4 frame each, one four-tone chord per frame. Command48: the fast profile's — a whole
// command in one 48-bit frame (sequence number, command, CRC-16) sent as two chords of
// 64-ary tones on the bins of a rectangular analysis window, answered by an ACK that names
// the frame's sequence number. Layouts in docs/protocol.md.
enum class FrameFormat { Word16, Command48 };

// The bin-centred tone plan of the Command48 format. Every tone sits on a bin of the
// rectangular analysis window (frequency = bin * rate / window_samples), so a window lying
// wholly inside a chord sees each tone in exactly one bin and nothing of its neighbours.
struct BinLink {
  int window_samples = 0;  // W; also the tone spacing: rate / W
  int hop_samples = 0;     // one analysis every hop; a chord lasts W + 2 * edge + hop
  int edge_samples = 0;    // raised-cosine fade at both ends of every chord
  std::array<int, 4> band_first_bin{};  // band b carries symbol values at first_bin + v
  int tones_per_band = 0;               // 64: six bits per band and chord
  int chords_per_frame = 0;             // 2: 48 bits
  double tone_amplitude = 0;            // linear, per tone
  double presence_db = 0;   // a band sounds when its best bin is this far above its floor
  double dominance_db = 0;  // ... and this far above the band's second-best bin
  double gone_db = 0;       // the other chord's tone must be this far below this chord's
  int absent_bands = 0;     // bands of a frame's eight that may fail presence_db (chased first)
  int chase_symbols = 0;    // least certain symbols whose runner-up is tried when the CRC fails
  // One verdict per frame (reliability/frame_gate.h), in analysis hops.
  double lockout_hops = 0;      // after an accept, candidates this long after are the same frame
  double cluster_gap_hops = 0;  // failed candidates this far apart are separate clusters
  double nack_settle_hops = 0;  // a failed cluster NACKs no earlier than this after its first
  // The sender's reply detector: two bands of 16 tones; ACK(seq) sounds tone seq in the
  // first and tone (5 seq + 3) mod 16 in the second, NACK tone 0 and tone 8.
  int reply_window_samples = 0;
  int reply_hop_samples = 0;
  int reply_edge_samples = 0;
  std::array<int, 2> reply_band_first_bin{};
  int reply_tones_per_band = 0;
  double reply_amplitude = 0;     // linear, per tone
  double reply_presence_db = 0;   // stricter than presence_db: 16 tones, one window, no CRC
  double reply_dominance_db = 0;  // stricter than dominance_db: speech has harmonics here

  int chord_samples() const { return window_samples + 2 * edge_samples + hop_samples; }
  int frame_samples() const { return chords_per_frame * chord_samples(); }
  // Two whole analysis windows fit in a reply, one hop apart: the sender wants both to agree.
  int reply_samples() const { return reply_window_samples + 2 * reply_edge_samples + 2 * reply_hop_samples; }
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
  FrameFormat frame_format = FrameFormat::Word16;
  BinLink bins;  // Command48 only

  int hop_samples() const;
  int samples_for_ms(double ms) const;
  // The slowest sample rate a recording may have and still carry the highest plan tone.
  int min_recording_rate_hz() const;
};

// The seed report's link.
const LinkProfile& seed_profile();

// A whole command per 48-bit frame in about 0.1 s: docs/protocol.md, "The fast profile".
const LinkProfile& fast_profile();

// Every profile this build knows, in the order `--profile` help lists them.
const std::vector<const LinkProfile*>& all_profiles();

// The profile called `name`; throws std::invalid_argument naming the known profiles.
const LinkProfile& profile_by_name(std::string_view name);

// "seed, fast" — for help texts and error messages.
std::string profile_names();

}  // namespace dtmf
