#include "link/command_frame_path.h"

#include <algorithm>

#include "command/command_payload.h"
#include "reliability/chase_decoder.h"
#include "signal/bin_synthesizer.h"

namespace dtmf::link {

PlannedCommandFrame plan_command_frame(const command::Command& command, std::uint8_t sequence) {
  PlannedCommandFrame p;
  const std::uint32_t payload = command::encode_payload(command);
  for (int step = 0; step <= reliability::kSequenceMask; ++step) {
    p.frame = reliability::CommandFrame{static_cast<std::uint8_t>((sequence + step) & reliability::kSequenceMask), payload};
    p.bits = reliability::pack(p.frame);
    p.symbols = reliability::to_symbols(p.bits);
    bool shared_tone = false;
    for (std::size_t b = 0; b < 4; ++b) shared_tone = shared_tone || p.symbols[b] == p.symbols[b + 4];
    if (!shared_tone) break;
  }
  return p;
}

std::vector<float> render_command_frame(const LinkProfile& profile, const PlannedCommandFrame& frame) {
  return signal::synthesize_symbols(profile, frame.symbols);
}

CommandFramePath::CommandFramePath(const LinkProfile& profile)
    : chase_symbols_(profile.bins.chase_symbols),
      frame_ms_(1000.0 * profile.bins.frame_samples() / profile.sample_rate_hz),
      hop_ms_(1000.0 * profile.bins.hop_samples / profile.sample_rate_hz),
      listener_(profile),
      // Candidates of one frame come from its inner window and up to two hops either side,
      // and for a few hops more its last chord and its echo in a room pair up with what
      // follows; the next frame's come a whole frame (ten hops) after its own. So after an
      // accept, seven hops are the frame's; a cluster ends after two and a half quiet hops.
      // A failed cluster waits a chord and three hops before its NACK: the pair of the last
      // frame's tail (in a room) and the next frame's first chord comes one chord (five hops)
      // before that frame's own pair, and its accept must be able to close the cluster.
      gate_(profile.bins.lockout_hops * hop_ms_, profile.bins.cluster_gap_hops * hop_ms_,
            profile.bins.nack_settle_hops * hop_ms_) {
  received_.reserve(16);
}

std::span<const ReceivedCommandFrame> CommandFramePath::feed(std::span<const float> samples) {
  received_.clear();
  for (const signal::FrameCandidate& c : listener_.feed(samples)) {
    if (follows_last_frame(c)) continue;
    reliability::SymbolReading reading;
    reading.symbols = c.symbols;
    reading.runner_up = c.runner_up;
    reading.certainty = c.certainty;
    if (const auto nack = gate_.on_time(c.heard_ms)) deliver(*nack);
    if (const auto verdict = gate_.on_candidate(c.start_ms, c.heard_ms, reliability::chase_decode(reading, chase_symbols_),
                                                reliability::from_symbols(c.symbols))) {
      deliver(*verdict);
    }
  }
  if (const auto nack = gate_.on_time(listener_.now_ms())) deliver(*nack);
  return received_;
}

// The last accepted frame's second chord paired with whatever follows it — the next
// frame's first chord, or its own echo in the room — looks like a frame too. It never
// passes the CRC, but it would end in a NACK that the sender takes for its next frame's.
// Such a pair starts before the last frame has ended, or (an echo, smeared by the room)
// has three or four of its first chord's symbols equal to the last frame's second chord.
bool CommandFramePath::follows_last_frame(const signal::FrameCandidate& c) const {
  if (!last_accepted_ || c.start_ms - last_start_ms_ > 3 * frame_ms_) return false;
  if (c.start_ms < last_start_ms_ + frame_ms_ - 1.5 * hop_ms_) return true;
  int same = 0;
  for (std::size_t b = 0; b < 4; ++b) same += c.symbols[b] == (*last_accepted_)[b + 4];
  return same >= 3;
}

void CommandFramePath::deliver(const reliability::Verdict& verdict) {
  ReceivedCommandFrame r;
  r.start_ms = verdict.start_ms;
  r.heard_ms = verdict.heard_ms;
  r.bits = verdict.read_bits;
  if (verdict.accepted) {
    r.bits = verdict.accepted->bits;
    const auto decoded = command::decode_payload(verdict.accepted->frame.payload);
    last_accepted_ = reliability::to_symbols(verdict.accepted->bits);
    last_start_ms_ = verdict.start_ms;
    if (decoded.command) {
      r.frame = verdict.accepted->frame;
      r.substitutions = verdict.accepted->substitutions;
      r.repeat = !sequence_.first_time(*r.frame);
      if (!r.repeat) r.command = decoded.command;
    } else {
      r.error = decoded.error;  // passed the CRC by chance: answered like any broken frame
    }
  }
  received_.push_back(std::move(r));
}

}  // namespace dtmf::link
