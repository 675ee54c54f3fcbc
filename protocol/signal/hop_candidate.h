// Signal layer: what the fast profile's frame listener hands on — a candidate frame's tone
// readings at one frequency-offset hypothesis — and the sink that takes them.
//
// A frame of `chords` chords sounds chord c on band set c % 2 (the even bands, then the odd
// ones, then the even ones again), so no chord's reverberant tail lies in the bands the next
// chord is read from; tone t = c * 8 + b is chord c's band b.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "profile/link_profile.h"

namespace dtmf::signal {

inline constexpr int kMaxFrameChords = 3;
inline constexpr int kMaxFrameTones = kMaxFrameChords * HopPlan::kBandsPerChord;  // 24
// Offset hypotheses a candidate window is read at: the tracked offset, none, and its own estimate.
inline constexpr std::size_t kOffsetHypotheses = 3;

// chord c of a frame, band b -> index into its tones; the band set chord c sounds on.
constexpr int hop_tone_index(int chord, int band) { return chord * HopPlan::kBandsPerChord + band; }
constexpr int hop_band_set(int chord) { return chord % 2; }

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

}  // namespace dtmf::signal
