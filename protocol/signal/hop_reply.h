// Signal layer: the fast profile's replies as audio, and the sender's listener for them.
//
// A reply is four tones, one in each of four bands of 8 tones 62.5 Hz apart (2.0-3.9 kHz,
// below the chords, so the robot may answer while a chord still sounds); which tones is the
// reliability layer's code (reliability/reply_code.h). The listener reads each band's best
// bin every 4 ms hop; a band counts when its bin stands `reply_presence_db` over the band's
// median and rose `reply_onset_db` since the window a reply earlier (not the tail of an
// earlier reply). `read` (the code) turns the four bands into a reply, or none; a reply read
// in two windows in a row is heard. It passes once, and again only after a window without it.
// Times are milliseconds since the first sample fed. Feeding allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_power.h"
#include "signal/sliding_window.h"

namespace dtmf::signal {

struct HeardReply {
  int reply = 0;  // what `read` returned
  double start_ms = 0;
  double heard_ms = 0;
};

class HopReplyListener {
 public:
  // `read`: the four bands' tones (-1 where a band was not heard) -> a reply id, or -1.
  using Read = std::function<int(const std::array<int, 4>& tones)>;
  HopReplyListener(const LinkProfile& profile, Read read);
  std::span<const HeardReply> feed(std::span<const float> samples);

 private:
  void analyze_window();

  const HopLink& hops_;
  Read read_;
  int sample_rate_hz_;
  float presence_ratio_;
  float onset_ratio_;
  int lo_bin_;
  int windows_back_;  // hops in one reply: the onset compares with that many windows earlier
  BinPower bins_;
  SlidingWindow window_;
  std::vector<std::vector<float>> ring_;  // powers of the last windows_back_ + 1 windows
  std::size_t newest_ = 0;
  long long windows_ = 0;
  int last_ = -1;    // the reply the previous window read, -1 none
  int passed_ = -1;  // the reply passed and not yet re-armed
  std::array<float, 16> scratch_{};
  std::vector<HeardReply> heard_;
};

}  // namespace dtmf::signal
