// Signal layer: the fast profile's frame listener — audio in, frame candidates out.
//
//   samples -> rectangular window (W samples, every hop H) -> BinPower (the bins of the 16 bands)
//           -> per bin: a background that may rise only slowly (steady tones: whines) and the
//              excess over it; per band: its best bin against its mean
//           -> for each frame shape (two chords, or three for an authenticated frame): the
//              window now (the last chord's bands) and the windows one and two chords earlier
//              (the earlier chords' bands): a candidate when every chord's bands stand out
//           -> per frequency-offset hypothesis, eight tone readings per chord (symbol,
//              certainty, heard) for the reliability layer's decoder
//
// A chord lasts W + 2 * edge + H samples, so exactly one grid window lies wholly inside each
// chord, and the one inside the next chord comes exactly one chord later. Chord c of a frame
// uses band set c % 2 (the even bands, then the odd ones, then the even ones again), so no
// chord's reverberant tail lies in the bands the next chord is read from. A two-chord frame
// never reads as the start of a three-chord one and back: the receive path judges both
// shapes under one frame gate (link/hop_frame_path.h). A tone counts as heard when its bin's excess stands
// `presence_db` over the band's median power and rose `onset_db` since the window a chord earlier (a reverberant tail,
// or any steady sound, decays or holds; a chord's tone starts). A steady whine is taken out before any of this: each
// bin's background follows a drop at once and a rise only at `background_rise_db_per_s`, and the readings use the
// excess over it. Clocks and Doppler shift every tone by the same factor (1 + offset): the readings are taken at each
// hypothesis's shifted bins — the offset tracked from the frames decoded before (confirm()), no offset, and an estimate
// from this candidate's own fractional peak positions — in that order, each built only when the one before did not
// decode (a sink says so), since most frames decode at the first. While the sink holds the listener (after an accept,
// the frame's later windows), no candidates are built at all.
// A window none of whose hypotheses was taken (or one a band short of the gate:
// `reread_gate_bands`), when the sink asks for it and no frame was taken in the
// `reread_delay_hops` windows after it (a window a hop early fails where the next one decodes),
// gets a second look: it is read once more over each chord's whole steady part, its start and
// offset searched afresh (whole_chord_reader.h): 1 dB more per tone, for the frames the grid's
// windows hear too weakly; then its grid hypotheses are offered again as they were. All are
// `second_look` candidates, heard when offered: the sink's place for costlier decoding.
// A grid candidate begins where the earliest of its first chord's heard tones rose across the
// windows (chord_onset.h): a clean frame decodes from windows astride its chords' starts, hops before
// the ones wholly inside them, so the decoding window's own position says little.
// Times are milliseconds since the first sample fed; the stream is taken to be preceded by
// silence. Once constructed, feeding allocates nothing. (Reading a window's tones, offset and
// start: hop_candidate_reading.cpp.)
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_power.h"
#include "signal/sliding_window.h"
#include "signal/steady_background.h"
#include "signal/whole_chord_reader.h"

namespace dtmf::signal {

inline constexpr int kMaxFrameChords = 3;
inline constexpr int kMaxFrameTones = kMaxFrameChords * HopPlan::kBandsPerChord;  // 24
// Offset hypotheses a candidate window is read at: the tracked offset, none, and its own estimate.
inline constexpr std::size_t kOffsetHypotheses = 3;

struct ToneReading {
  std::uint8_t symbol = 0;  // the strongest tone of its band
  float certainty = 1;      // its power over the runner-up's (>= 1)
  bool heard = true;        // false: no tone stood out there, or it did not rise with the chord
  bool risen = true;        // it rose with the chord (a tail, or a steady sound, does not)
  int runner_up = -1;       // the band's second strongest tone
};

struct HopCandidate {
  int chords = 2;             // the frame shape: 2 chords, or 3 (authenticated)
  double start_ms = 0;        // when the first chord began (its earliest tone's rise; a re-read: 1 ms)
  double heard_ms = 0;        // end of the window in the last chord; a second look's: when offered
  int offset_ppm = 0;         // the frequency offset these readings assume
  bool whole_chords = false;  // read again over each chord's whole steady part
  bool second_look = false;   // offered again after `reread_delay_hops` with nothing taken (so are re-reads)
  std::array<ToneReading, kMaxFrameTones> tones{};  // first chord's bands, then the next chord's
  std::array<float, kMaxFrameTones> peak_bins{};    // each band's peak, in fractional bins (offset tracking)
  std::size_t tone_count() const { return static_cast<std::size_t>(chords * HopPlan::kBandsPerChord); }
};

// Where a window's candidates go, hypothesis after hypothesis.
class CandidateSink {
 public:
  virtual ~CandidateSink() = default;
  // True when the candidate is taken (its frame decoded): no further hypothesis is built.
  // A `second_look` candidate comes only when nothing was taken since its window: the place
  // for costlier decoding, which a clean frame's next window then never needs.
  virtual bool take(const HopCandidate& candidate) = 0;
  // No hypothesis of the window was taken; `first` is the first of them. True when the
  // window is worth a second look (a frame the sink could take may be in it).
  virtual bool none_taken(const HopCandidate& first) = 0;
};

class HopListener {
 public:
  explicit HopListener(const LinkProfile& profile);

  // Every hypothesis of every candidate window within `samples` (for tests and tools); the
  // span is valid until the next call.
  std::span<const HopCandidate> feed(std::span<const float> samples);
  // The receive path's way: candidates to `sink` as they come.
  void feed(std::span<const float> samples, CandidateSink& sink);
  // No candidates for windows ending before `until_ms` (the accepted frame's own windows).
  void hold_until(double until_ms) { hold_until_ms_ = until_ms; }
  // A frame was decoded from `candidate` with these code symbols (tone_count() of them): the
  // offset its tones show is the first hypothesis for the frames that follow.
  void confirm(const HopCandidate& candidate, std::span<const std::uint8_t> symbols);
  std::optional<int> tracked_offset_ppm() const { return tracked_ppm_; }
  // End of the latest analysed window.
  double now_ms() const { return analysed_until_ms_; }
  double hop_ms() const { return 1000.0 * hop_ / sample_rate_hz_; }

 private:
  // power: raw |X|^2 of bins [lo_bin_, hi_bin_); excess: power over the background.
  struct Window : ChordPowers {
    // The band's best excess over its mean power, band set s, band b at [s * 8 + b].
    std::array<float, 2 * HopPlan::kBandsPerChord> band_score{};
  };
  void analyze_window(CandidateSink& sink);
  // The candidates of the frame shape of `chords` ending in the newest window.
  void offer_shape(int chords, CandidateSink& sink);
  // The window inside chord c of a frame of `chords` ending now; c = -1: one chord before it.
  const Window& chord_window(int chords, int c) const;
  enum class Gate { Closed, RereadOnly, Open };
  Gate gate(int chords) const;
  // Keeps a window for a second look: its grid hypotheses (none for a window short of the gate).
  void keep_for_reread(int chords, std::span<const HopCandidate> hypotheses);
  HopCandidate make_candidate(int chords, int offset_ppm);
  // Where the first chord of `c` began (the earliest rise of its heard tones across the windows),
  // or nothing when fewer than half of them rose clearly where the grid could have read the frame.
  std::optional<long long> first_chord_start_sample(const HopCandidate& c) const;
  // Readings of a frame of `chords` from windows[c + 1] for chord c (windows[0]: a chord
  // before the frame), taken at the bins of `offset_ppm`.
  HopCandidate read_candidate(int chords, int offset_ppm, std::span<const ChordPowers* const> windows) const;
  // A window none of whose hypotheses was taken, kept for a second look.
  struct Pending {
    int chords = 2;
    long long end_sample = 0;  // its window's end
    std::size_t hypotheses = 0;
    std::array<HopCandidate, kOffsetHypotheses> grid{};  // the grid's readings, as offered
  };
  void reread_pending(CandidateSink& sink);
  // The pending window read again over each chord's whole steady part, or nothing when the
  // history no longer holds it.
  std::optional<HopCandidate> read_whole_chords(const Pending& p, long long now);
  int blind_offset_ppm(int chords) const;
  // chord c of a frame, band b -> index into its tones; the band set chord c sounds on
  static int tone_index(int chord, int band) { return chord * HopPlan::kBandsPerChord + band; }
  static int band_set(int chord) { return chord % 2; }

  // Room either side of a band for tones moved by a frequency offset, and for a guard bin.
  static constexpr int kMarginBins = 4;

  const HopPlan& hops_;
  int sample_rate_hz_;
  int hop_;
  int hops_per_chord_;
  float presence_ratio_;
  float onset_ratio_;
  float gate_ratio_;
  int lo_bin_;  // first bin analysed: the lowest band, less room for offsets
  int hi_bin_;
  BinPower bins_;
  SlidingWindow window_;
  SteadyBackground background_;
  std::vector<Window> ring_;  // the last kMaxFrameChords * hops_per_chord + 1 + reread_delay_hops windows
  std::size_t newest_ = 0;
  long long windows_ = 0;
  double analysed_until_ms_ = 0;
  std::optional<int> tracked_ppm_;
  double hold_until_ms_ = -1e300;
  std::vector<HopCandidate> found_;
  std::array<HopCandidate, kOffsetHypotheses> offered_{};  // the newest window's hypotheses, as offered
  WholeChordReader reread_;
  std::array<ChordPowers, kMaxFrameChords + 1> reread_windows_;
  std::array<Pending, 8> pending_{};  // two shapes a window: the newest and the delay's windows
  std::size_t pending_count_ = 0;
  long long taken_at_sample_ = -1;              // the end of the latest window a candidate was taken in
  mutable std::vector<float> scratch_;          // a band's tones' excess (readings)
  mutable std::vector<float> floor_;            // ... and their raw power (the floor)
  mutable std::vector<float> onset_amplitude_;  // a first-chord tone, window by window (start)
};

}  // namespace dtmf::signal
