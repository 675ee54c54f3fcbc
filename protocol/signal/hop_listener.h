// Signal layer: the fast profile's frame listener — audio in, frame candidates out.
//
//   samples -> rectangular window (W samples, every hop H) -> BinPower (the bins of the 16 bands)
//           -> per bin: a background that may rise only slowly (steady tones: whines) and the
//              excess over it; per band: its score                       (HopBandGate::score)
//           -> for each frame shape (two chords, or three for an authenticated frame): the
//              window now (the last chord's bands) and the windows one and two chords earlier
//              (the earlier chords' bands): a candidate when every chord's bands stand out
//                                                                          (HopBandGate::judge)
//           -> per frequency-offset hypothesis, eight tone readings per chord (symbol,
//              certainty, heard) for the reliability layer's decoder      (HopReader)
//           -> windows nothing was taken from wait for a second look       (RereadQueue)
//
// A chord lasts W + 2 * edge + H samples, so exactly one grid window lies wholly inside each
// chord, and the one inside the next chord comes exactly one chord later (hop_candidate.h has
// the band sets). A two-chord frame never reads as the start of a three-chord one and back:
// the receive path judges both shapes under one frame gate (link/hop_frame_path.h).
// Clocks and Doppler shift every tone by the same factor (1 + offset): the readings are taken
// at each hypothesis's shifted bins — the offset tracked from the frames decoded before
// (HopOffsetTracker), no offset, and an estimate from this candidate's own fractional peak
// positions — in that order, each built only when the one before did not decode (a sink says
// so), since most frames decode at the first.
//
// Its state, window by window, named as liquid-dsp's frame synchronisers name theirs:
//   DetectFrame  every window is gated for each frame shape; where the gate opens, the
//                hypotheses are read and offered; where it opens only for a re-read, or none
//                was taken, the window is queued for a second look;
//   HoldFrame    the sink took a frame and holds the listener until its last window has
//                passed (hold_until): the windows are analysed (the background learns) but
//                offer nothing; then DetectFrame again.
// In either state, a queued window whose delay has passed with nothing taken gets its second
// look: read once more over each chord's whole steady part, its start and offset searched
// afresh (whole_chord_reader.h), 1 dB more per tone for the frames the grid's windows hear
// too weakly; then its grid hypotheses are offered again as they were. All are `second_look`
// candidates: the sink's place for costlier decoding.
// Times are milliseconds since the first sample fed; the stream is taken to be preceded by
// silence. Once constructed, feeding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_power.h"
#include "signal/hop_band_gate.h"
#include "signal/hop_candidate.h"
#include "signal/hop_offset_tracker.h"
#include "signal/hop_reader.h"
#include "signal/hop_window_history.h"
#include "signal/reread_queue.h"
#include "signal/sliding_window.h"
#include "signal/steady_background.h"
#include "signal/whole_chord_reader.h"

namespace dtmf::signal {

class HopListener {
 public:
  enum class Phase { DetectFrame, HoldFrame };

  explicit HopListener(const LinkProfile& profile);

  // Every hypothesis of every candidate window within `samples` (for tests and tools); the
  // span is valid until the next call.
  std::span<const HopCandidate> feed(std::span<const float> samples);
  // The receive path's way: candidates to `sink` as they come.
  void feed(std::span<const float> samples, CandidateSink& sink);
  // HoldFrame: no candidates for windows ending before `until_ms` (the accepted frame's own windows).
  void hold_until(double until_ms);
  // A frame was decoded from `candidate` with these code symbols (tone_count() of them): the
  // offset its tones show is the first hypothesis for the frames that follow.
  void confirm(const HopCandidate& candidate, std::span<const std::uint8_t> symbols) {
    offset_.confirm(candidate, symbols);
  }
  std::optional<int> tracked_offset_ppm() const { return offset_.offset_ppm(); }
  Phase phase() const { return phase_; }
  // End of the latest analysed window.
  double now_ms() const { return analysed_until_ms_; }
  double hop_ms() const { return 1000.0 * hop_ / sample_rate_hz_; }

 private:
  // Windows of a frame of `chords` ending now: [0] the one a chord before its first chord,
  // [c + 1] the one inside chord c.
  using FrameWindows = std::array<const HopWindow*, kMaxFrameChords + 1>;
  void analyze_window(CandidateSink& sink);
  FrameWindows frame_windows(int chords) const;
  // DetectFrame, for the frame shape of `chords` ending in the newest window.
  void detect_frame(int chords, CandidateSink& sink);
  HopCandidate make_candidate(int chords, int offset_ppm, const FrameWindows& windows) const;
  void second_looks(CandidateSink& sink);
  // A queued window read again over each chord's whole steady part, or nothing when the
  // history no longer holds it.
  std::optional<HopCandidate> read_whole_chords(const PendingWindow& p, long long now);

  const HopPlan& hops_;
  int sample_rate_hz_;
  int hop_;
  int hops_per_chord_;
  int lo_bin_;  // first bin analysed: the lowest band, less room for offsets
  int hi_bin_;
  BinPower bins_;
  SlidingWindow window_;
  SteadyBackground background_;
  HopWindowHistory history_;
  HopBandGate gate_;
  HopReader reader_;
  HopOffsetTracker offset_;
  RereadQueue rereads_;
  WholeChordReader whole_chords_;
  std::array<ChordPowers, kMaxFrameChords + 1> whole_chord_windows_;
  Phase phase_ = Phase::DetectFrame;
  double hold_until_ms_ = -1e300;
  long long windows_ = 0;
  double analysed_until_ms_ = 0;
  long long taken_at_sample_ = -1;  // the end of the latest window a candidate was taken in
  std::vector<HopCandidate> found_;
  std::array<HopCandidate, kOffsetHypotheses> offered_{};  // the newest window's hypotheses, as offered
};

}  // namespace dtmf::signal
