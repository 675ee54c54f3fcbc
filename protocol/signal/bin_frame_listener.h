// Signal layer, part 9: the fast profile's frame listener — audio in, frame candidates out.
//
//   samples -> rectangular window (W samples, every hop H) -> BinBands (4 bands x 64 tones)
//           -> the window now and the window one chord (a whole number of hops) earlier
//           -> a candidate: eight 6-bit symbols with their runner-ups and certainties
//
// A chord lasts W + 2 * edge + H samples, so exactly one grid window lies wholly inside
// each chord, and the window inside the second chord comes exactly one chord after the one
// inside the first. A pair of windows is a candidate when all but `absent_bands` of the
// eight bands sound, and each chord's tones are gone from the other's window (a sustained
// note or a hum sounds in both; a frame's two chords never do). Two windows reading the same
// symbol in a band where both sound are no frame either: senders never put the same tone in
// both chords of a frame (link/command_frame_path.h), while one chord seen twice, a held
// sound, or a seed chord (tones in two or three of these bands, noise in the rest) always
// does. Whether the symbols form a
// frame is the reliability layer's question (CRC-16 with a chase of runner-ups).
// Times are milliseconds since the first sample fed; the stream is taken to be preceded by
// silence. Once constructed, feeding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_bands.h"
#include "signal/sliding_window.h"

namespace dtmf::signal {

inline constexpr int kFrameBands = 8;  // two chords of four bands

struct FrameCandidate {
  double start_ms = 0;  // when the first chord began (within a hop)
  double heard_ms = 0;  // end of the window inside the second chord
  std::array<std::uint8_t, kFrameBands> symbols{};
  std::array<std::uint8_t, kFrameBands> runner_up{};
  std::array<float, kFrameBands> certainty{};  // best / runner-up power; absent bands 1
  int absent = 0;                              // bands that did not sound
};

class BinFrameListener {
 public:
  explicit BinFrameListener(const LinkProfile& profile);

  // Candidates found within `samples`; the span is valid until the next call.
  std::span<const FrameCandidate> feed(std::span<const float> samples);
  // End of the latest analysed window.
  double now_ms() const { return analysed_until_ms_; }
  double hop_ms() const { return 1000.0 * hop_ / sample_rate_hz_; }
  void reset();

 private:
  struct WindowRecord {
    std::array<BandReading, 4> readings{};
    std::vector<float> powers;  // 4 bands x tones
  };
  void analyze_window();
  bool chords_apart(const WindowRecord& first, const WindowRecord& second) const;

  const BinLink& bins_;
  int sample_rate_hz_;
  int hop_;
  int hops_per_chord_;
  float gone_ratio_;
  float presence_ratio_;
  BinBands bands_;
  SlidingWindow window_;  // the latest W samples, analysed every hop
  std::vector<WindowRecord> ring_;  // the last hops_per_chord + 1 windows
  std::size_t newest_ = 0;
  long long windows_ = 0;
  double analysed_until_ms_ = 0;
  std::vector<FrameCandidate> found_;
};

}  // namespace dtmf::signal
