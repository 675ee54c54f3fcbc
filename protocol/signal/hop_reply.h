// Signal layer: the sender's listener for the fast profile's replies — audio in, readings of
// the reply's twelve tones out.
//
// A reply is two chords, each one tone in each of six bands of 4 tones 125 Hz apart
// (0.47-3.41 kHz, below the chords, so the robot may answer while a chord sounds), read in
// 32 ms windows (in a room a shorter tone smears into the bins beside it); which
// tones is the reliability layer's reply code (reliability/reply_code.h). Every hop the
// latest window is read through a Hann window: the sender's own frames, 20 dB louder at its
// microphone than the answer, sit at 4 kHz and up, and a Hann window's sidelobes fall far
// enough that nothing of them reaches the reply bands (a rectangular window's fall 6 dB an
// octave). A bin's steady background (a fan's whine) is learnt and taken off as in the frame
// listener. The window now reads the second chord and the window one reply chord earlier the
// first; a band's tone is the strongest of its bins that rose `reply_onset_db` since the
// chord before (for the first chord, the window before the reply; for the second, the first
// chord's: a tail holds or falls, and no reply repeats a band's tone), heard when its excess
// stands `reply_presence_db` over the band's median. Each window is read once per reply lane
// (answers alternate lanes two bins apart: profile/link_profile.h, link/reply_lane.h), and a
// lane's reading whose two chords hear at least `min_heard` tones is given. Times are
// milliseconds since the first sample fed. Feeding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "reliability/reply_code.h"
#include "signal/bin_power.h"
#include "signal/sliding_window.h"
#include "signal/steady_background.h"

namespace dtmf::signal {

// The profile's reply plan and the reliability layer's reply code count the same tones.
static_assert(HopPlan::kReplyTones == reliability::kReplyTones);
static_assert(HopPlan::kReplyBands == reliability::kReplyBandsPerChord);
static_assert(HopPlan::kReplyToneValues == reliability::kReplyToneValues);

struct HeardReading {
  reliability::ReplyReading tones{};  // -1 where not heard
  int heard = 0;                      // tones heard
  double start_ms = 0;                // when the reply began (within a hop)
  double heard_ms = 0;                // end of the window inside its second chord
  long long window = 0;               // the window's number: readings of consecutive windows are one reply
  int lane = 0;                       // the reply lane read
};

class HopReplyListener {
 public:
  HopReplyListener(const LinkProfile& profile, int min_heard);
  std::span<const HeardReading> feed(std::span<const float> samples);
  double hop_ms() const { return 1000.0 * hops_.reply_hop_samples / sample_rate_hz_; }

 private:
  void analyze_window();
  int read_band(const std::vector<float>& excess, const std::vector<float>& power, const std::vector<float>& before,
                int lane, int band, int exclude);
  void read_lane(int lane, std::size_t first, std::size_t before);

  const HopPlan& hops_;
  int min_heard_;
  int sample_rate_hz_;
  float presence_ratio_;
  float onset_ratio_;
  int lo_bin_;
  int hops_per_chord_;
  BinPower bins_;
  SlidingWindow window_;
  SteadyBackground background_;
  std::vector<std::vector<float>> power_ring_;   // raw power of the last 2 * hops_per_chord_ + 1 windows
  std::vector<std::vector<float>> excess_ring_;  // ... and its excess over the background
  std::size_t newest_ = 0;
  long long windows_ = 0;
  std::vector<HeardReading> heard_;
};

}  // namespace dtmf::signal
