// Signal layer: the fast profile's frames and replies as audio.
//
// A frame is two chords of eight tones (three for an authenticated frame): code symbol
// t = 8 c + b sounds in chord c at bin band_first_bin[c % 2][b] + symbol (frequency = bin *
// rate / window_samples), so consecutive chords alternate between the two band sets. Each chord lasts
// window + 2 * edge + hop samples with raised-cosine fades of `edge_samples`, so one analysis
// window of the grid lies wholly inside it. The tones of a chord start at fixed, spread
// phases (Newman's b^2 pi / 8) rather than all at zero, so eight tones of 0.1 rarely add up
// to more than half their 0.8 worst case. A reply is two chords of six tones, one per reply
// band (signal/hop_reply.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "reliability/reply_code.h"
#include "reliability/tag_chord.h"

namespace dtmf::signal {

inline constexpr int kHoppedFrameTones = 2 * HopPlan::kBandsPerChord;
using HoppedSymbols = std::array<std::uint8_t, kHoppedFrameTones>;  // first chord's eight, then the second's

// Frequencies of the frame's tones (eight per chord), first chord first.
std::vector<double> frame_tones_hz(const LinkProfile& profile, std::span<const std::uint8_t> symbols);
// The frame's chords, symbols.size() / 8 of them, each hops.chord_samples() long.
std::vector<float> synthesize_hopped_frame(const LinkProfile& profile, std::span<const std::uint8_t> symbols);
// A reply: two chords of six tones, tones[6 c + b] in reply band b of chord c, in reply lane
// `lane` (hops.reply_samples() long).
std::vector<float> synthesize_hopped_reply(const LinkProfile& profile, const reliability::ReplyTones& tones, int lane);
// A tagged ACK: symbols[k] in band k (band set k / 8, band k % 8), hops.tag_samples() long.
std::vector<float> synthesize_tag_chord(const LinkProfile& profile, const reliability::TagChordSymbols& symbols);

}  // namespace dtmf::signal
