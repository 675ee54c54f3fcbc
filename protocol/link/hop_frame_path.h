// The fast profile's receive path through the signal and reliability layers, for frames of
// both shapes: two chords (50 bits, unauthenticated) and three (80 bits, authenticated).
//
//   audio -> HopListener (candidates of either shape: tone readings per frequency-offset hypothesis,
//            and a failed window's second look when this path says it could use one)
//         -> Reed-Solomon + CRC (reliability/frame_code.h, reliability/sealed_frame.h), hypotheses in order;
//            runner-up swaps only at a second look (a clean frame's next window decodes plainly)
//         -> FrameGate (one verdict per frame, whatever its shape: accepted once, or one NACK
//            for a failed cluster; the first two chords of an authenticated frame fail as a
//            two-chord frame and belong to its cluster)
//         -> the same bits again within repeat_guard_ms: the same sound (an echo), dropped;
//            and the frame accepted last, read again where most of its tones did not rise
//            with their chords: its reverberant tail (in a quiet room it stays over the
//            floor for most of a second), dropped
// A damaged frame whose MAC was checked and failed (its CRC held after corrections) is a
// refusal for authentication, not a broken frame: where none_taken would NACK it as damaged,
// its verdict carries the decoded bits as intact, so that the admission refuses it and the
// log counts it with the forgeries (same NACK on air; noise that passes no frame-like gate
// still makes no verdict at all).
// An authenticated frame's MAC is checked for at most kMacChecksPerFrame different frames
// read between two verdicts, or in one run of candidates (the same bits read again cost no
// check): a forger gets that many guesses at a 32-bit MAC per frame he plays, and no more
// (docs/security.md).
// Every verdict is reported, intact or not; what it means to the robot (a command, a repeat,
// a refusal) is the admission's to say (frame_admission.h).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "profile/link_profile.h"
#include "reliability/frame_bits.h"
#include "reliability/frame_gate.h"
#include "reliability/sealed_frame.h"
#include "signal/hop_listener.h"

namespace dtmf::link {

struct HeardHopFrame {
  double start_ms = 0;
  double heard_ms = 0;
  int chords = 2;               // 2: a 50-bit frame, 3: an 80-bit authenticated one
  bool intact = false;          // passed the code and the CRC (and for 3 chords its MAC, or it is refused)
  reliability::FrameBits bits;  // as accepted; for a failed frame, as first read
  int offset_ppm = 0;           // the frequency offset it was heard at
};

inline constexpr int kMacChecksPerFrame = 4;

class HopFramePath final : private signal::CandidateSink {
 public:
  // `authentic`: whether an 80-bit frame whose CRC holds is authentic (its MAC holds): the
  // robot's admission says, and decoding goes on past a frame it would refuse. Empty: no key.
  // `plain_taken`: whether the robot may take a two-chord (unauthenticated) frame at all; a
  // robot that refuses them tries no runner-up swaps on them (they could only find a frame to
  // refuse, whose lockout would hide the authenticated frame its chords belong to).
  HopFramePath(const LinkProfile& profile, reliability::SealedCheck authentic, bool plain_taken = true);
  std::span<const HeardHopFrame> feed(std::span<const float> samples);

 private:
  bool take(const signal::HopCandidate& candidate) override;
  bool none_taken(const signal::HopCandidate& first) override;
  void deliver(const reliability::Verdict& verdict, int offset_ppm);
  bool checked_authentic(const reliability::FrameBits& bits);
  bool rose_with_its_chords(const signal::HopCandidate& c) const;
  bool shadow_of_accepted(const signal::HopCandidate& c) const;

  const HopPlan& hops_;
  reliability::SealedCheck authentic_;
  bool plain_taken_;
  int plain_chase_tones_;              // the profile's chase_tones, or 0 where plain frames are refused
  int sealed_chase_tones_;             // the profile's chase_tones, or 0 without a key
  reliability::SealedCheck budgeted_;  // authentic_ within the per-frame budget
  std::array<std::pair<reliability::FrameBits, bool>, kMacChecksPerFrame> checked_{};
  int checks_ = 0;
  // The last decode whose CRC held and whose MAC failed, and when its candidate was heard.
  std::optional<std::pair<double, reliability::FrameBits>> mac_failed_;
  double candidate_heard_ms_ = 0;  // the candidate being decoded
  double last_candidate_ms_ = -1e300;
  signal::HopListener listener_;
  reliability::FrameGate gate_;
  std::optional<reliability::FrameBits> last_bits_;
  double last_start_ms_ = -1e300;
  double last_end_ms_ = -1e300;
  std::vector<HeardHopFrame> received_;
};

}  // namespace dtmf::link
