// Signal layer, part 10: the fast profile's reply listener — the sender hears ACK(seq) / NACK.
//
//   samples -> rectangular window (reply W, every reply hop) -> BinBands (2 bands x 16 tones)
//           -> ACK(seq): tone seq, then tone (5 seq + 3) mod 16; NACK: tone 0, then tone 8
//              -> two agreeing windows in a row -> one reply
//
// The ACK names the sequence number of the frame it answers, so the sender can tell an
// answer to its current frame from a late answer to an earlier one. Both bands must sound
// (BinBands' presence test, and a dominance test stricter than the frames': speech puts
// several harmonics of like level in each band) and agree with each other: a random pair
// of tones is an ACK with odds of 1 in 16, and two windows in a row must say the same. A reply
// passes once; it passes again only after a window without it.
// Times are milliseconds since the first sample fed. Feeding allocates nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_bands.h"
#include "signal/sliding_window.h"

namespace dtmf::signal {

inline constexpr std::uint8_t kNackSecondTone = 8;

struct NamedReply {
  bool ack = false;
  std::uint8_t sequence = 0;  // ACK only
  bool operator==(const NamedReply&) const = default;
};

struct HeardReply {
  NamedReply reply;
  double start_ms = 0;
  double heard_ms = 0;
};

// The two tone indexes of a reply.
std::array<int, 2> reply_tone_indexes(const NamedReply& reply);
// ACK(seq) sounds tone seq in the first band and this one in the second: a permutation, so
// that the two tones are not a fixed distance apart (a voice whose pitch divides that
// distance would sound such pairs all the time).
int ack_second_tone(int sequence);

class BinReplyListener {
 public:
  explicit BinReplyListener(const LinkProfile& profile);

  std::span<const HeardReply> feed(std::span<const float> samples);
  void reset();

 private:
  void analyze_window();

  int sample_rate_hz_;
  int window_samples_;
  int hop_;
  BinBands bands_;
  SlidingWindow window_;
  std::optional<NamedReply> previous_;  // what the last window read
  std::optional<NamedReply> passed_;    // passed and not yet re-armed
  std::vector<HeardReply> heard_;
};

}  // namespace dtmf::signal
