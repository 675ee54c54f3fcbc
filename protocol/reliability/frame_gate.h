// Reliability layer: one verdict per frame heard — accepted once, or one NACK.
//
// The listener offers a candidate in every window that looks like a frame: the window
// wholly inside it and, at lower certainty, its neighbours a hop either side. The gate
// turns a run of such candidates into one verdict. A candidate whose frame passed the
// check is accepted, and every candidate within `lockout_ms` after it is dropped (they are
// the same frame seen again). Candidates that all fail form a cluster, whatever their
// shape (the first two chords of an authenticated frame fail as a two-chord frame); a
// cluster that held an intact frame (its CRC held, its MAC not) ends with that frame; once no candidate
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

#include "reliability/frame_bits.h"

namespace dtmf::reliability {

// A candidate's frame as the gate sees it: its shape and bits, decoded or only read.
struct GateFrame {
  int chords = 2;       // its shape
  FrameBits bits;       // as decoded, or as first read (a failed cluster's, for logs)
  bool intact = false;  // a failed candidate whose check held all the same (its MAC did not)
};

struct Verdict {
  double start_ms = 0;    // when the frame began sounding
  double heard_ms = 0;    // when the verdict was reached
  bool accepted = false;  // false: a failed cluster — NACK, or refused when `frame.intact`
  GateFrame frame;
};

class FrameGate {
 public:
  FrameGate(double lockout_ms, double cluster_gap_ms, double settle_ms = 0);

  // A candidate heard at `heard_ms`: its frame, and whether it decoded (passed the check).
  std::optional<Verdict> on_candidate(double start_ms, double heard_ms, bool decoded, const GateFrame& frame = {});
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
  GateFrame cluster_frame_;
};

}  // namespace dtmf::reliability
