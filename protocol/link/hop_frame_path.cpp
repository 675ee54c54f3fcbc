#include "link/hop_frame_path.h"

#include <algorithm>
#include <cmath>

#include "reliability/command_frame.h"
#include "reliability/frame_code.h"
#include "reliability/sealed_frame.h"

namespace dtmf::link {

HopFramePath::HopFramePath(const LinkProfile& profile, reliability::SealedCheck authentic, bool plain_taken)
    : hops_(profile.hops()),
      authentic_(std::move(authentic)),
      plain_taken_(plain_taken),
      plain_chase_tones_(plain_taken ? profile.hops().chase_tones : 0),
      // Without a key nothing sealed is authentic: runner-up swaps could find nothing the
      // robot may take (a refusal keeps more parity).
      sealed_chase_tones_(authentic_ ? profile.hops().chase_tones : 0),
      budgeted_([this](const reliability::FrameBits& bits) { return checked_authentic(bits); }),
      listener_(profile),
      // Candidates of one frame come from its inner window and a hop or two either side:
      // after an accept, seven hops are the frame's. Failed candidates belong to one cluster
      // while they come less than a chord and a hop apart (the two-chord reading of an
      // authenticated frame's start and its three-chord reading a chord later), and a failed
      // cluster waits two chords and three hops before its NACK, so that an accept of the
      // frame's longer reading can close it silently.
      gate_(profile.hops().lockout_hops * listener_.hop_ms(), profile.hops().cluster_gap_hops * listener_.hop_ms(),
            profile.hops().nack_settle_hops * listener_.hop_ms()) {
  received_.reserve(8);
}

std::span<const HeardHopFrame> HopFramePath::feed(std::span<const float> samples) {
  received_.clear();
  listener_.feed(samples, *this);
  if (const auto nack = gate_.on_time(listener_.now_ms())) deliver(*nack, 0);
  return received_;
}

namespace {

// A runner-up goes to the decoder only where it came within `clear_certainty` of the tone
// read: one beaten by more is seldom the tone sent, and swapping it would only cost tries (the
// windows between two clean frames read as one frame, every tone clear and the word wrong).
template <std::size_t N>
std::array<reliability::SymbolReading, N> readings_of(const signal::HopCandidate& c, float clear_certainty) {
  std::array<reliability::SymbolReading, N> r{};
  for (std::size_t t = 0; t < N; ++t) {
    const auto& tone = c.tones[t];
    r[t] = {tone.symbol, tone.certainty, tone.heard, tone.risen,
            tone.certainty < clear_certainty ? tone.runner_up : -1};
  }
  return r;
}

}  // namespace

bool HopFramePath::take(const signal::HopCandidate& c) {
  if (const auto nack = gate_.on_time(c.heard_ms)) deliver(*nack, 0);
  // Candidates a cluster's gap apart belong to different frames: each its own budget.
  if (c.heard_ms - last_candidate_ms_ > hops_.cluster_gap_hops * listener_.hop_ms()) checks_ = 0;
  // (Every candidate is heard when offered, a second look too: the times never go back.)
  last_candidate_ms_ = c.heard_ms;
  std::optional<reliability::FrameBits> bits;
  // Runner-up swaps (up to 63 more decodes a hypothesis) only at a second look: a clean
  // frame's window a hop early fails its plain tries, and the next window decodes plainly.
  // (A profile without second looks swaps at once.)
  const bool swaps = c.second_look || hops_.reread_delay_hops == 0;
  if (c.chords == 2) {
    if (const auto d = reliability::decode_frame(readings_of<reliability::kCodeSymbols>(c, hops_.clear_certainty),
                                                 hops_.max_erasures, swaps ? plain_chase_tones_ : 0)) {
      bits = d->bits;
      listener_.confirm(c, reliability::command_frame_symbols(d->bits));
    }
  } else {
    candidate_heard_ms_ = c.heard_ms;
    const auto d = reliability::decode_sealed(readings_of<reliability::kSealedSymbols>(c, hops_.clear_certainty),
                                              hops_.sealed_max_erasures, budgeted_, swaps ? sealed_chase_tones_ : 0);
    if (d.authentic) {
      bits = d.authentic->bits;
      listener_.confirm(c, reliability::sealed_frame_symbols(d.authentic->bits));
    } else if (d.intact && !shadow_of_accepted(c)) {
      // Intact but not authentic: a later window may still read the real frame; if none does,
      // the cluster ends with this one, refused.
      gate_.on_candidate(c.start_ms, c.heard_ms, false, {c.chords, d.intact->bits, true});
      return false;
    }
  }
  if (!bits) return false;
  if (*bits == last_bits_ && !rose_with_its_chords(c)) return true;  // the last frame's tail: taken, and dropped
  if (const auto verdict = gate_.on_candidate(c.start_ms, c.heard_ms, true, {c.chords, *bits})) {
    // The frame's later windows would only read it again: build no candidates from them.
    listener_.hold_until(c.heard_ms + hops_.lockout_hops * listener_.hop_ms());
    deliver(*verdict, c.offset_ppm);
  }
  return true;
}

// A candidate that begins while the frame accepted last sounded reads that frame's chords in
// the other shape (its two chords and what follows them as three, an authenticated frame's
// first two or last two as a frame of two, or in a room a chord and its echo a few hops
// later): no frame of its own, nothing to NACK. A sender's next frame begins after its last
// has ended.
bool HopFramePath::shadow_of_accepted(const signal::HopCandidate& c) const {
  const double slack_ms = 1.5 * listener_.hop_ms();
  return c.start_ms > last_start_ms_ - slack_ms && c.start_ms < last_end_ms_ - slack_ms;
}

bool HopFramePath::none_taken(const signal::HopCandidate& first) {
  if (shadow_of_accepted(first)) return false;
  // Read again over whole chords only a shape the robot may take: without a key a sealed
  // frame could only be refused, and a robot refusing plain frames takes no two-chord one.
  // (Asking only for readings with a tone or two heard clearly would spare the re-reads of a
  // seed chord, whose tones lie between this grid's bins, but at -12 dB it lost 1 % of frames.)
  const bool worth_rereading = first.chords == 2 ? plain_taken_ : static_cast<bool>(authentic_);
  // (A cluster already holding an intact frame ends with it whatever this candidate adds.)
  // Only what sounded like a frame — as many tones heard clearly as decoding needs — and still
  // did not decode is a damaged frame to NACK: a seed chord or a whistle that passed the gate is not.
  const int max_erasures = first.chords == 2 ? hops_.max_erasures : hops_.sealed_max_erasures;
  int clear = 0;
  for (std::size_t t = 0; t < first.tone_count(); ++t) {
    clear += first.tones[t].heard && first.tones[t].certainty >= hops_.clear_certainty ? 1 : 0;
  }
  if (clear < static_cast<int>(first.tone_count()) - max_erasures) return worth_rereading;
  // A frame that decoded and failed its MAC is one to refuse (authentication), not a damaged one.
  const bool mac_failed = first.chords != 2 && mac_failed_ && mac_failed_->first == first.heard_ms;
  const reliability::FrameBits read =
      mac_failed ? mac_failed_->second
      : first.chords == 2
          ? reliability::FrameBits(
                reliability::read_bits(readings_of<reliability::kCodeSymbols>(first, hops_.clear_certainty)))
          : reliability::read_sealed_bits(readings_of<reliability::kSealedSymbols>(first, hops_.clear_certainty));
  if (const auto verdict =
          gate_.on_candidate(first.start_ms, first.heard_ms, false, {first.chords, read, mac_failed})) {
    deliver(*verdict, first.offset_ppm);
  }
  return worth_rereading;
}

// Most of the candidate's tones rose with their chords (more than the code may erase did not).
bool HopFramePath::rose_with_its_chords(const signal::HopCandidate& c) const {
  int unrisen = 0;
  for (std::size_t t = 0; t < c.tone_count(); ++t) unrisen += c.tones[t].risen ? 0 : 1;
  return unrisen <= (c.chords == 2 ? hops_.max_erasures : hops_.sealed_max_erasures);
}

bool HopFramePath::checked_authentic(const reliability::FrameBits& bits) {
  if (!authentic_) return false;
  for (int i = 0; i < checks_; ++i) {
    const auto& [checked, held] = checked_[static_cast<std::size_t>(i)];
    if (checked != bits) continue;
    if (!held) mac_failed_ = {candidate_heard_ms_, bits};
    return held;
  }
  if (checks_ == kMacChecksPerFrame) return false;
  const bool holds = authentic_(bits);
  checked_[static_cast<std::size_t>(checks_++)] = {bits, holds};
  if (!holds) mac_failed_ = {candidate_heard_ms_, bits};
  return holds;
}

void HopFramePath::deliver(const reliability::Verdict& verdict, int offset_ppm) {
  checks_ = 0;  // a new frame, a new budget
  HeardHopFrame r;
  r.start_ms = verdict.start_ms;
  r.heard_ms = verdict.heard_ms;
  r.chords = verdict.frame.chords;
  r.intact = verdict.accepted || verdict.frame.intact;
  r.bits = verdict.frame.bits;
  r.offset_ppm = offset_ppm;
  if (r.intact) {
    // The same frame accepted again before a retransmission could have come: the room
    // gave its sound back (a strong reflection) — the same transmission, not a new one.
    if (last_bits_ == r.bits && verdict.start_ms - last_start_ms_ < hops_.repeat_guard_ms) return;
    last_bits_ = r.bits;
    last_start_ms_ = verdict.start_ms;
    const double chord_ms = listener_.hop_ms() * hops_.chord_samples() / hops_.hop_samples;
    last_end_ms_ = verdict.start_ms + verdict.frame.chords * chord_ms;
  }
  received_.push_back(r);
}

}  // namespace dtmf::link
