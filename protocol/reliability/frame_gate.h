// Reliability layer: one verdict per frame heard — accepted once, or one NACK.
//
// The listener offers a candidate in every window that looks like a frame: the window
// wholly inside it and, at lower certainty, its neighbours a hop either side. The gate
// turns a run of such candidates into one verdict. A candidate whose frame passed the
// check is accepted, and every candidate within `lockout_ms` after it is dropped (they are
// the same frame seen again). Candidates that all fail form a cluster; once no candidate
// has come for `cluster_gap_ms`, and `settle_ms` has passed since its first candidate, the
// cluster ends in one NACK, so the sender retransmits. A frame accepted before then closes
// the cluster silently: in a room, the tail of one frame pairs with the first chord of the
// next (sent right after the ACK) a chord before that frame's own pair is heard.
// A frame that passes again later (an echo, or the sender's retransmission after a lost
// ACK) is accepted again: telling those apart is the sequence number's job
// (sequence_filter.h), and the ACK for it names its sequence number so no other frame can
// take it as its own. Pure logic: times are the caller's; nothing is allocated.
#pragma once

#include <cstdint>
#include <optional>

#include "reliability/frame_code.h"

namespace dtmf::reliability {

struct Verdict {
  double start_ms = 0;                   // when the frame began sounding
  double heard_ms = 0;                   // when the verdict was reached
  std::optional<DecodedFrame> accepted;  // nullopt: NACK
  std::uint64_t read_bits = 0;           // NACK: what the cluster's first candidate read (for logs)
};

class FrameGate {
 public:
  FrameGate(double lockout_ms, double cluster_gap_ms, double settle_ms = 0);

  // A candidate heard at `heard_ms` reading `read_bits`, and what decoding made of it.
  std::optional<Verdict> on_candidate(double start_ms, double heard_ms, const std::optional<DecodedFrame>& frame,
                                      std::uint64_t read_bits = 0);
  // Time has reached `now_ms` (after every window): a failed cluster may end in a NACK.
  std::optional<Verdict> on_time(double now_ms);
  void reset();

 private:
  double lockout_ms_;
  double cluster_gap_ms_;
  double settle_ms_;
  double locked_until_ms_ = -1e300;
  bool cluster_open_ = false;
  double cluster_start_ms_ = 0;
  double cluster_first_ms_ = 0;  // when its first candidate was heard
  double cluster_last_ms_ = 0;
  std::uint64_t cluster_bits_ = 0;
};

}  // namespace dtmf::reliability
