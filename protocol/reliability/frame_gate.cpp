#include "reliability/frame_gate.h"

namespace dtmf::reliability {

FrameGate::FrameGate(double lockout_ms, double cluster_gap_ms, double settle_ms)
    : lockout_ms_(lockout_ms), cluster_gap_ms_(cluster_gap_ms), settle_ms_(settle_ms) {}

void FrameGate::reset() {
  locked_until_ms_ = -1e300;
  cluster_open_ = false;
}

std::optional<Verdict> FrameGate::on_candidate(double start_ms, double heard_ms,
                                               const std::optional<DecodedFrame>& frame, std::uint64_t read_bits) {
  if (heard_ms <= locked_until_ms_) return std::nullopt;
  if (frame) {
    cluster_open_ = false;
    locked_until_ms_ = heard_ms + lockout_ms_;
    return Verdict{start_ms, heard_ms, frame, 0};
  }
  if (!cluster_open_) {
    cluster_open_ = true;
    cluster_start_ms_ = start_ms;
    cluster_first_ms_ = heard_ms;
    cluster_bits_ = read_bits;
  }
  cluster_last_ms_ = heard_ms;
  return std::nullopt;
}

std::optional<Verdict> FrameGate::on_time(double now_ms) {
  if (!cluster_open_ || now_ms - cluster_last_ms_ < cluster_gap_ms_ || now_ms - cluster_first_ms_ < settle_ms_) {
    return std::nullopt;
  }
  cluster_open_ = false;
  return Verdict{cluster_start_ms_, now_ms, std::nullopt, cluster_bits_};
}

}  // namespace dtmf::reliability
