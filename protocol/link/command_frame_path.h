// Both paths of the fast profile (Command48 format) through the layers.
//
// Sender: command -> 28-bit payload -> 48-bit frame with sequence number and CRC-16 ->
//         eight 6-bit symbols -> two chords of audio.
// Robot:  audio -> BinFrameListener (candidates) -> chase decoder + FrameGate (one verdict
//         per frame) -> sequence filter (a retransmission is answered, not re-executed) ->
//         payload -> command.
// Every verdict is reported, accepted or not, so the caller can answer it — ACK naming the
// frame's sequence number, or NACK — and log it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "command/command.h"
#include "profile/link_profile.h"
#include "reliability/command_frame.h"
#include "reliability/frame_gate.h"
#include "reliability/sequence_filter.h"
#include "signal/bin_frame_listener.h"

namespace dtmf::link {

struct PlannedCommandFrame {
  reliability::CommandFrame frame;
  std::uint64_t bits = 0;
  reliability::Symbols symbols{};
};

// The frame of `command` with sequence number `sequence`, or the next number whose frame has
// no tone in both chords (the listener takes a band's tone in both chords for one chord seen
// twice, or for a seed chord; about one frame in 16 needs the next number, and a run of
// more than a few is practically impossible). The caller numbers its next command from the returned
// frame's number. Throws command::ParameterError for an out-of-range parameter.
PlannedCommandFrame plan_command_frame(const command::Command& command, std::uint8_t sequence);
// The frame's two chords (profile.bins.frame_samples() long).
std::vector<float> render_command_frame(const LinkProfile& profile, const PlannedCommandFrame& frame);

struct ReceivedCommandFrame {
  double start_ms = 0;
  double heard_ms = 0;
  std::optional<reliability::CommandFrame> frame;  // nullopt: not intact, answer NACK
  std::uint64_t bits = 0;                          // as accepted; for a NACK, as first read
  int substitutions = 0;                           // symbols the chase replaced
  bool repeat = false;                             // same sequence and bits as the last executed
  std::optional<command::Command> command;         // for new intact frames
  std::string error;                               // why an intact-looking frame was refused
};

class CommandFramePath {
 public:
  explicit CommandFramePath(const LinkProfile& profile);

  // Verdicts reached within `samples`; valid until the next call.
  std::span<const ReceivedCommandFrame> feed(std::span<const float> samples);

 private:
  void deliver(const reliability::Verdict& verdict);
  bool follows_last_frame(const signal::FrameCandidate& candidate) const;

  int chase_symbols_;
  double frame_ms_;
  double hop_ms_;
  std::optional<reliability::Symbols> last_accepted_;
  double last_start_ms_ = 0;
  signal::BinFrameListener listener_;
  reliability::FrameGate gate_;
  reliability::SequenceFilter sequence_;
  std::vector<ReceivedCommandFrame> received_;
};

}  // namespace dtmf::link
