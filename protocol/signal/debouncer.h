// Signal layer: the debouncer that turns repeated detections into one event.
//
// Seed section 8: a symbol (a chord's 16 bits, or ACK/NACK) passes after `min_detections`
// detections of it within `window_ms`; the symbol that passed is then ignored for
// `lockout_ms`; any other symbol passes as soon as it has its own detections.
// Ours on top: the symbol that passed also stays ignored until it is re-armed — by a window
// without it, or by a dip of `rearm_drop_db` below its peak followed by a rise of as much
// again (a new onset). For twice the lockout after a pass, detections of that symbol
// rearm_drop_db or more below its peak are its reverberant tail: they neither count nor
// re-arm. A chord stretched past the lockout by a room's reverberation thus passes once,
// while the same chord sent again after a gap passes again, even when the reverberation
// fills the gap.
// And against dropouts: a sender kept off the CPU plays its chord with a hole in it, and
// the rest of the chord, heard after the lockout, looks like the same chord sent again.
// The two differ only in length: the rest is shorter than a chord. So the symbol that
// passed keeps a tally of the time it sounded (windows that hear it within rearm_drop_db of
// its peak); while it comes back within symbol_ms + max_dropout_ms of its first detection,
// it passes again only once the tally exceeds symbol_ms + presence_margin_ms. A chord sent
// again right after the first thus passes about 0.2 s later than it would have; one sent
// after a longer pause (a retransmission) is not delayed.
//
// The caller reports every analysis window, with or without a detection. Pure logic:
// times are the caller's (milliseconds of audio); nothing is allocated.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "profile/link_profile.h"

namespace dtmf::signal {

class Debouncer {
 public:
  struct Detection {
    std::uint32_t symbol;
    double level;  // linear amplitude; only ratios matter
  };
  struct Pass {
    std::uint32_t symbol;
    double first_detection_ms;  // the earliest detection that counted
    double pass_ms;             // the detection that completed it
  };

  explicit Debouncer(const DebounceParams& params);

  // One analysis window ending at t_ms, and what it detected (if anything).
  std::optional<Pass> on_window(double t_ms, std::optional<Detection> detection);
  void reset();

 private:
  struct Counted {
    std::uint32_t symbol;
    double t_ms;
  };
  static constexpr std::size_t kCapacity = 64;

  bool locked_out(const Detection& detection, double t_ms);
  // The symbol that passed, back before it could have ended: its resumption, not a repeat.
  bool still_sounding_once(double t_ms) const;

  DebounceParams params_;
  double rearm_ratio_;
  std::array<Counted, kCapacity> recent_{};  // ring buffer, oldest at head_
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::optional<std::uint32_t> locked_symbol_;
  double locked_until_ms_ = 0;
  double locked_peak_level_ = 0;  // loudest since the pass
  double locked_dip_level_ = 0;   // quietest since that peak
  bool rearmed_ = true;
  double locked_first_ms_ = 0;   // the first detection of the symbol that passed
  double sounded_ms_ = 0;        // how long it has sounded since, in windows
  double last_window_ms_ = 0;    // the previous window's time, for the hop
  bool locked_sounded_ = false;  // it sounded in the previous window ...
  double locked_onset_ms_ = 0;   // ... and the window it last came back in
};

}  // namespace dtmf::signal
