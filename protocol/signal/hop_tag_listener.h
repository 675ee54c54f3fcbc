// Signal layer: the keyed sender's listener for tagged ACKs — audio in, readings of the tag
// chord's sixteen bands out (reliability/tag_chord.h).
//
// A tagged ACK is one chord of a frame's shape with a tone in every one of the frame's sixteen
// bands. Every hop the latest window (rectangular, as the frame listener reads: the tones sit
// on its bins) is read at each of the profile's frequency offsets (`tag_offset_ppm`: the
// robot's clock and its motion move every tone by the same factor). A band's candidates are
// its bins that stand `tag_presence_db` over the band's median and rose `tag_onset_db` since
// the quietest earlier window that does not overlap this one, up to `tag_onset_lookback_hops`
// back: a tail falls, the sender's own frame's included, and a robot farther away answers
// later, when the window a chord earlier holds the cut-off end of the sender's frame, loud in
// every bin. They are ranked by how much they rose: the room's reflections of the frame's end
// ring on in the answer's window, loud but risen less. The listener knows nothing of the tag
// awaited: the link checks each reading against it. A window is handed over only when some
// offset heard as many bands as a tag needs. Times are milliseconds since the first sample
// fed. Feeding allocates nothing.
#pragma once

#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "reliability/tag_chord.h"
#include "signal/bin_power.h"
#include "signal/sliding_window.h"

namespace dtmf::signal {

static_assert(HopPlan::kTagOffsets == reliability::kTagChordHypotheses);
static_assert(2 * HopPlan::kBandsPerChord == reliability::kTagChordTones);

struct HeardTagChord {
  reliability::TagChordReading reading{};
  double heard_ms = 0;   // the end of the window read
  long long window = 0;  // the window's number
};

class HopTagListener {
 public:
  explicit HopTagListener(const LinkProfile& profile);
  std::span<const HeardTagChord> feed(std::span<const float> samples);

 private:
  void analyze_window();
  void read_band(int offset, int band, const std::vector<float>& power, const std::vector<float>& quietest,
                 std::array<std::int8_t, reliability::kTagChordCandidates>& out) const;

  const HopPlan& hops_;
  int sample_rate_hz_;
  float presence_ratio_;
  float onset_ratio_;
  int lo_bin_;
  int first_clear_hops_;  // the nearest earlier window that does not overlap the newest
  // first_bin_[offset][band]: band's value 0 at that offset, as an index into a window's powers.
  std::array<std::array<int, reliability::kTagChordTones>, HopPlan::kTagOffsets> first_bin_{};
  BinPower bins_;
  SlidingWindow window_;
  std::vector<std::vector<float>> power_ring_;  // the last tag_onset_lookback_hops + 1 windows
  std::vector<float> quietest_;                 // each bin's least power in the earlier windows
  std::size_t newest_ = 0;
  long long windows_ = 0;
  std::vector<HeardTagChord> heard_;
};

}  // namespace dtmf::signal
