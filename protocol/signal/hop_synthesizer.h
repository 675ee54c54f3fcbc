// Signal layer: the fast profile's frames and replies as audio.
//
// A frame is two chords of eight tones: code symbol t = 8 c + b sounds in chord c at bin
// band_first_bin[c][b] + symbol (frequency = bin * rate / window_samples). Each chord lasts
// window + 2 * edge + hop samples with raised-cosine fades of `edge_samples`, so one analysis
// window of the grid lies wholly inside it. The tones of a chord start at fixed, spread
// phases (Newman's b^2 pi / 8) rather than all at zero, so eight tones of 0.1 rarely add up
// to more than half their 0.8 worst case. A reply is four tones, one per reply band.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "profile/link_profile.h"

namespace dtmf::signal {

inline constexpr int kHoppedFrameTones = 2 * HopLink::kBandsPerChord;
using HoppedSymbols = std::array<std::uint8_t, kHoppedFrameTones>;  // first chord's eight, then the second's

// Frequencies of the frame's sixteen tones, first chord first.
std::array<double, kHoppedFrameTones> frame_tones_hz(const LinkProfile& profile, const HoppedSymbols& symbols);
// The frame's two chords (hops.frame_samples() long).
std::vector<float> synthesize_hopped_frame(const LinkProfile& profile, const HoppedSymbols& symbols);
// A reply of four tones, tone_index[b] in reply band b (hops.reply_samples() long).
std::vector<float> synthesize_hopped_reply(const LinkProfile& profile, const std::array<std::uint8_t, 4>& tone_index);

}  // namespace dtmf::signal
