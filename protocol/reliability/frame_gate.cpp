#include "reliability/frame_gate.h"

namespace dtmf::reliability {

FrameGate::FrameGate(double lockout_ms, double cluster_gap_ms, double settle_ms)
    : lockout_ms_(lockout_ms), cluster_gap_ms_(cluster_gap_ms), settle_ms_(settle_ms) {}

void FrameGate::reset() {
  locked_until_ms_ = -1e300;
  cluster_open_ = false;
}

std::optional<Verdict> FrameGate::on_candidate(double start_ms, double heard_ms, bool decoded, const GateFrame& frame) {
  if (heard_ms <= locked_until_ms_) return std::nullopt;
  if (decoded) {
    cluster_open_ = false;
    locked_until_ms_ = heard_ms + lockout_ms_;
    return Verdict{start_ms, heard_ms, true, frame};
  }
  if (!cluster_open_) {
    cluster_open_ = true;
    cluster_start_ms_ = start_ms;
    cluster_first_ms_ = heard_ms;
    cluster_frame_ = frame;
  } else if (frame.intact && !cluster_frame_.intact) {
    cluster_frame_ = frame;
  }
  cluster_last_ms_ = heard_ms;
  return std::nullopt;
}

std::optional<Verdict> FrameGate::on_time(double now_ms) {
  if (!cluster_open_ || now_ms - cluster_last_ms_ < cluster_gap_ms_ || now_ms - cluster_first_ms_ < settle_ms_) {
    return std::nullopt;
  }
  cluster_open_ = false;
  return Verdict{cluster_start_ms_, now_ms, false, cluster_frame_};
}

}  // namespace dtmf::reliability
