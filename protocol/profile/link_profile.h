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
#include <variant>
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
  double chord_ms = 0;           // one command frame on air
  double gap_ms = 0;             // silence between two frames from the sender
  double ack_ms = 0;             // the robot's ACK / NACK chord
  double ack_timeout_ms = 0;     // from the start of a frame's chord until it counts as unanswered
  int auto_retransmissions = 0;  // retransmissions before the caller is asked
  // A frame no robot answers (a stop for every robot) is sent this many times, each copy
  // numbered anew: no answer tells the sender it was heard (0: the format cannot send one).
  int broadcast_copies = 0;
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
  int peak_count = 0;            // the N loudest peaks considered
  double noise_gate_dbfs = 0;    // peaks below this (as a sine amplitude) are ignored
  double tone_tolerance_hz = 0;  // how far a peak may sit from a plan tone and still match it
  double dominance_db = 0;       // a band's tone must stand this far above its other plan tones
  // The sender's and the robot's clocks differ and the robot moves: every tone of a chord is
  // off by the same factor. The decoder tries factors within this many ppm and keeps the
  // one under which the peaks sit closest to plan tones (0: none tried).
  double max_offset_ppm = 0;
  // A chord is refused when at least this many other peaks are as loud as its weakest tone:
  // a crowded spectrum is another link's chords or music, not ours (0: no limit).
  int crowding_peaks = 0;
  // Each bin's steady level (a whine) is learnt and taken off before peaks are sought; it
  // may rise at most this fast, so a chord's tone never becomes background (0: off).
  double background_rise_db_per_s = 0;
};

// When a detected chord becomes a frame.
struct DebounceParams {
  int min_detections = 0;    // detections of the same chord needed ...
  double window_ms = 0;      // ... within this time
  double lockout_ms = 0;     // after a pass, the same chord is ignored this long ...
  double rearm_drop_db = 0;  // ... and until it has faded this far (or gone) in some window
  // A symbol that comes back within symbol_ms + max_dropout_ms of its first detection passes
  // again only once it has sounded longer in all than one symbol can, by presence_margin_ms:
  // until then it is the same symbol resumed after a dropout (signal/debouncer.h).
  // symbol_ms is the listener's (a chord's or a reply's length); 0 turns the rule off.
  double symbol_ms = 0;
  double max_dropout_ms = 0;
  double presence_margin_ms = 0;
};

// How a command travels: each wire format has a plan of its own, and a profile holds one
// (LinkProfile::plan). Only protocol/link reads which: it picks the link that implements it.
//
// WordPlan (the seed's): RESET, mode and parameter words, one 16-bit CRC-4 frame each, one
// four-tone chord per frame, found by an FFT's peaks and debounced.
struct WordPlan {
  TonePlan tones;
  AnalysisParams analysis;
  DetectorParams robot_detector;   // hears command chords
  DetectorParams sender_detector;  // hears ACK / NACK chords
  DebounceParams debounce;
};

// HopPlan (the fast profile's): a whole command in one 50-bit frame (address, sequence
// number, command, CRC-16) coded as a Reed–Solomon codeword of sixteen 32-ary tones on two
// chords with disjoint tone sets, answered by an ACK that names the frame's sequence number.
// Layouts in docs/protocol.md. Every tone sits on a bin of a
// rectangular analysis window (frequency = bin * rate / window_samples), so a window lying
// wholly inside a chord sees each tone in one bin. The two chords of a frame use disjoint
// sets of bands (frequency hopping, as NATO's JANUS does): one chord's reverberant tail
// lies in bands the next chord's symbols are not read from.
struct HopPlan {
  static constexpr int kBandsPerChord = 8;
  int window_samples = 0;           // W; also the tone spacing: rate / W
  int hop_samples = 0;              // one analysis every hop; a chord lasts W + 2 * edge + hop
  int edge_samples = 0;             // raised-cosine fade at both ends of every chord
  int chords_per_frame = 0;         // an unauthenticated frame
  int sealed_chords_per_frame = 0;  // an authenticated frame (reliability/sealed_frame.h)
  int tones_per_band = 0;           // 32: one 5-bit Reed-Solomon symbol per band and chord
  // band_first_bin[c][b]: chord c's band b carries symbol values at first_bin + v.
  std::array<std::array<int, kBandsPerChord>, 2> band_first_bin{};
  double tone_amplitude = 0;  // linear, per tone
  double gate_db = 0;  // a candidate when gate_bands of each chord's bands have a bin this far over the band's mean
  int gate_bands = 0;
  double presence_db = 0;               // a band is heard when its best bin stands this far over the band's median
  double onset_db = 0;                  // ... and rose this much since the window a chord earlier (no tail)
  float clear_certainty = 0;            // a tone over its band's runner-up by this much is clearly heard:
                                        // a cluster that fails to decode NACKs only with 16 - max_erasures such
  double background_rise_db_per_s = 0;  // how fast a bin's steady background may rise (whines)
  int max_erasures = 0;                 // tones the decoder may erase (unheard, or least certain first)
  int sealed_max_erasures = 0;          // ... in an authenticated frame
  int chase_tones = 0;                  // then the least certain tones swapped for their runner-ups
  int max_offset_ppm = 0;               // the frequency offsets (clocks, Doppler) searched for
  // A candidate no hypothesis decoded, and no frame taken within this many hops after it, is
  // read again over each chord's whole steady part (signal/whole_chord_reader.h); 0: never.
  int reread_delay_hops = 0;
  int reread_step_samples = 0;  // the step of the search for where the chords' steady parts begin
  int reread_gate_bands = 0;    // a window short of the gate with this many loud bands in every chord
                                // (and half of all) is re-read without the grid's tries
  // One verdict per frame (reliability/frame_gate.h), in analysis hops.
  double lockout_hops = 0;
  double cluster_gap_hops = 0;
  double nack_settle_hops = 0;
  double repeat_guard_ms = 0;  // the same frame accepted again this soon is the same sound
  // The robot's answers, below the chords so it may answer while a chord sounds: two chords
  // (a reply window wholly inside each, read with a Hann window) of one tone in each of
  // kReplyBands bands of kReplyToneValues (signal/hop_reply.h); which tones is the reliability
  // layer's reply code (reliability/reply_code.h). reply_tone_bin[b][v]: band b's tone v, in
  // bins of the reply window, in lane 0; lane l lies l * reply_lane_step_bins higher. Answers
  // to consecutive frames go in alternate lanes (reliability::reply_lane), so one answer's
  // reverberant tail never sits on the bins of the next.
  static constexpr int kReplyBands = 6;
  static constexpr int kReplyLanes = 2;
  static constexpr int kReplyToneValues = 4;
  static constexpr int kReplyChords = 2;
  static constexpr int kReplyTones = kReplyBands * kReplyChords;
  int reply_window_samples = 0;
  int reply_hop_samples = 0;
  int reply_edge_samples = 0;
  int reply_tones_per_band = 0;
  std::array<std::array<int, kReplyToneValues>, kReplyBands> reply_tone_bin{};
  int reply_lane_step_bins = 0;
  double reply_amplitude = 0;  // linear, per tone
  double reply_presence_db = 0;
  double reply_onset_db = 0;
  double reply_background_rise_db_per_s = 0;
  int reply_tones_needed = 0;  // tones of 12 that must agree with a named reply
  // The ACK to an authenticated frame: one chord of a frame's shape (chord_samples() long)
  // with a tone in each of the sixteen bands of both band sets (reliability/tag_chord.h), read
  // by the sender every hop at each of kTagOffsets frequency offsets (signal/hop_tag_listener.h).
  static constexpr int kTagOffsets = 5;
  double tag_amplitude = 0;  // linear, per tone
  double tag_presence_db = 0;
  double tag_onset_db = 0;
  // ... since the quietest of the windows from a window's length to this many hops earlier. A
  // robot d metres away answers 2 d / 343 s later than one beside the sender: a window a
  // chord before the tag's first may then hold the end of the sender's own frame, whose
  // cut-off spreads over the band 20 dB louder than the tag (signal/hop_tag_listener.h).
  int tag_onset_lookback_hops = 0;
  std::array<int, kTagOffsets> tag_offset_ppm{};
  // The tag chord sounds in the frame bands, where the sender's microphone hears its own frame
  // 20 dB louder: it begins tag_after_frame_ms after the frame has ended, so that a window of
  // the sender's lies wholly inside it and after its own chord's end (a chord cut off within a
  // window spreads over its whole band). The guard covers where the robot placed the frame's
  // start, to within a few milliseconds; the next frame waits tag_late_ms more for the same
  // uncertainty (docs/protocol.md, FrameStart).
  double tag_after_frame_ms = 0;
  double tag_late_ms = 0;

  int chord_samples() const { return window_samples + 2 * edge_samples + hop_samples; }
  int frame_samples() const { return chords_per_frame * chord_samples(); }
  int sealed_frame_samples() const { return sealed_chords_per_frame * chord_samples(); }
  // One whole reply window fits in each reply chord, which is a whole number of reply hops.
  int reply_chord_samples() const { return reply_window_samples + 2 * reply_edge_samples + reply_hop_samples; }
  int reply_samples() const { return kReplyChords * reply_chord_samples(); }
  int tag_samples() const { return chord_samples(); }
  // How long an authenticated frame keeps the frame bands busy: itself, the gap, its tag
  // chord and the robot's lateness.
  double sealed_bands_busy_ms(int sample_rate_hz) const {
    return 1000.0 * (sealed_frame_samples() + tag_samples()) / sample_rate_hz + tag_after_frame_ms + tag_late_ms;
  }
  int reply_bin(int lane, int band, int tone) const {
    return reply_tone_bin[static_cast<std::size_t>(band)][static_cast<std::size_t>(tone)] + lane * reply_lane_step_bins;
  }
};

// What every profile has, whatever its format, and its format's own plan.
struct LinkProfile {
  std::string name;
  std::string description;
  int sample_rate_hz = 0;
  LinkTiming timing;
  std::variant<WordPlan, HopPlan> plan;

  // The format's plan; std::invalid_argument naming the profile if it has another format.
  const WordPlan& words() const;
  WordPlan& words();
  const HopPlan& hops() const;
  HopPlan& hops();

  // The receiver's analysis hop: the audio block that suits it.
  int hop_samples() const;
  int samples_for_ms(double ms) const;
  // The loudest a command chord's tone sounds (linear, full scale = 1.0).
  double tone_amplitude() const;
  // The slowest sample rate a recording may have and still carry the highest plan tone.
  int min_recording_rate_hz() const;
};

// The seed report's link.
const LinkProfile& seed_profile();

// A whole command per frame in about 0.1 s, built for rooms: docs/protocol.md §10.
const LinkProfile& fast_profile();

// Every profile this build knows, in the order `--profile` help lists them.
const std::vector<const LinkProfile*>& all_profiles();

// The profile called `name`; throws std::invalid_argument naming the known profiles.
const LinkProfile& profile_by_name(std::string_view name);

// "seed, fast" — for help texts and error messages.
std::string profile_names();

}  // namespace dtmf
