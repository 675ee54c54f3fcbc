#include "link/hop_frame_path.h"

#include "command/command_payload.h"

namespace dtmf::link {

HopFramePath::HopFramePath(const LinkProfile& profile)
    : hops_(profile.hops),
      listener_(profile),
      // Candidates of one frame come from its inner window and a hop or two either side:
      // after an accept, seven hops are the frame's. Failed candidates 2.5 hops apart are
      // separate clusters, and a failed cluster waits a chord and three hops before its
      // NACK, so that an accept of the frame a hop later can close it silently.
      gate_(profile.hops.lockout_hops * listener_.hop_ms(), profile.hops.cluster_gap_hops * listener_.hop_ms(),
            profile.hops.nack_settle_hops * listener_.hop_ms()) {
  received_.reserve(8);
}

std::span<const ReceivedHopFrame> HopFramePath::feed(std::span<const float> samples) {
  received_.clear();
  listener_.feed(samples, *this);
  if (const auto nack = gate_.on_time(listener_.now_ms())) deliver(*nack, 0);
  return received_;
}

namespace {
std::array<reliability::SymbolReading, reliability::kCodeSymbols> readings_of(const signal::HopCandidate& c) {
  std::array<reliability::SymbolReading, reliability::kCodeSymbols> r{};
  for (std::size_t t = 0; t < r.size(); ++t) r[t] = {c.tones[t].symbol, c.tones[t].certainty, c.tones[t].heard};
  return r;
}
}  // namespace

bool HopFramePath::take(const signal::HopCandidate& c) {
  if (const auto nack = gate_.on_time(c.heard_ms)) deliver(*nack, 0);
  const auto decoded = reliability::decode_frame(readings_of(c), hops_.max_erasures);
  if (!decoded) return false;
  if (const auto verdict = gate_.on_candidate(c.start_ms, c.heard_ms, decoded, 0)) {
    listener_.confirm(c, reliability::encode_symbols(decoded->bits));
    // The frame's later windows would only read it again: build no candidates from them.
    listener_.hold_until(c.heard_ms + hops_.lockout_hops * listener_.hop_ms());
    deliver(*verdict, c.offset_ppm);
  }
  return true;
}

void HopFramePath::none_taken(const signal::HopCandidate& first) {
  // Only what sounded like a frame — as many tones heard clearly as decoding needs — and still
  // did not decode is a damaged frame to NACK: a seed chord or a whistle that passed the gate is not.
  int clear = 0;
  for (const auto& tone : first.tones) clear += tone.heard && tone.certainty >= hops_.clear_certainty ? 1 : 0;
  if (clear < reliability::kCodeSymbols - hops_.max_erasures) return;
  if (const auto verdict = gate_.on_candidate(first.start_ms, first.heard_ms, std::nullopt,
                                              reliability::read_bits(readings_of(first)))) {
    deliver(*verdict, first.offset_ppm);
  }
}

void HopFramePath::deliver(const reliability::Verdict& verdict, int offset_ppm) {
  ReceivedHopFrame r;
  r.start_ms = verdict.start_ms;
  r.heard_ms = verdict.heard_ms;
  r.bits = verdict.read_bits;
  r.offset_ppm = offset_ppm;
  if (verdict.accepted) {
    r.bits = verdict.accepted->bits;
    // The same frame accepted again before a retransmission could have come: the room
    // gave its sound back (a strong reflection) — the same transmission, not a new one.
    if (last_bits_ == r.bits && verdict.start_ms - last_start_ms_ < hops_.repeat_guard_ms) return;
    // Another robot's frame: not ours to answer (address 0 is every robot's).
    if (verdict.accepted->frame.address != 0) return;
    last_bits_ = r.bits;
    last_start_ms_ = verdict.start_ms;
    const auto decoded = command::decode_payload(verdict.accepted->frame.payload);
    if (decoded.command) {
      r.frame = verdict.accepted->frame;
      r.repeat = !sequence_.first_time(*r.frame);
      if (!r.repeat) r.command = decoded.command;
    } else {
      r.error = decoded.error;  // passed the checks by chance, or a kind this robot lacks: NACK
    }
  }
  received_.push_back(std::move(r));
}

}  // namespace dtmf::link
