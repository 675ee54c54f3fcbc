// The fast profile's receive path through the layers (FrameFormat::HoppedCommand).
//
//   audio -> HopListener (candidates: sixteen tone readings per frequency-offset hypothesis)
//         -> Reed-Solomon + CRC-16 (reliability/frame_code.h), hypotheses in order
//         -> FrameGate (one verdict per frame: accepted once, or one NACK for a failed cluster)
//         -> the same frame again within repeat_guard_ms: the same sound, dropped
//         -> SequenceFilter (a retransmission after a lost ACK is answered, not re-executed)
//         -> payload -> command
// Every verdict is reported, accepted or not, so the caller can answer it — ACK naming the
// frame's sequence number, or NACK — and log it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "command/command.h"
#include "profile/link_profile.h"
#include "reliability/frame_gate.h"
#include "reliability/sequence_filter.h"
#include "signal/hop_listener.h"

namespace dtmf::link {

struct ReceivedHopFrame {
  double start_ms = 0;
  double heard_ms = 0;
  std::optional<reliability::CommandFrame> frame;  // nullopt: not intact, answer NACK
  std::uint64_t bits = 0;                          // the 50 bits as accepted; for a NACK, as first read
  int offset_ppm = 0;                              // the frequency offset it was heard at
  bool repeat = false;                             // same frame as the last executed
  std::optional<command::Command> command;         // for new intact frames
  std::string error;                               // why an intact frame was refused
};

class HopFramePath final : private signal::CandidateSink {
 public:
  explicit HopFramePath(const LinkProfile& profile);
  std::span<const ReceivedHopFrame> feed(std::span<const float> samples);

 private:
  bool take(const signal::HopCandidate& candidate) override;
  void none_taken(const signal::HopCandidate& first) override;
  void deliver(const reliability::Verdict& verdict, int offset_ppm);

  const HopLink& hops_;
  signal::HopListener listener_;
  reliability::FrameGate gate_;
  reliability::SequenceFilter sequence_;
  std::optional<std::uint64_t> last_bits_;
  double last_start_ms_ = -1e300;
  std::vector<ReceivedHopFrame> received_;
};

}  // namespace dtmf::link
