// Signal layer, part 11: the fast profile's chords as audio.
//
// A frame is two chords, each chord_samples long (window + two edges + one hop), the first
// carrying symbols 0..3 and the second 4..7; band b's symbol v sounds on bin
// band_first_bin[b] + v, i.e. at exactly (first_bin + v) * rate / window Hz. Chords fade in
// and out over edge_samples (synthesizer.h's raised cosine), so the chord switch does not
// splatter into the other chord's bins or the reply bands. A reply is one two-tone chord.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_frame_listener.h"
#include "signal/bin_reply_listener.h"

namespace dtmf::signal {

// The eight tones of a frame: the first chord's four bands, then the second's.
std::array<double, kFrameBands> symbol_tones_hz(const LinkProfile& profile,
                                                const std::array<std::uint8_t, kFrameBands>& symbols);
// The two chords of a frame whose symbols are `symbols` (frame_samples long).
std::vector<float> synthesize_symbols(const LinkProfile& profile, const std::array<std::uint8_t, kFrameBands>& symbols);

// An ACK naming `reply.sequence`, or a NACK (reply_samples long).
std::vector<float> synthesize_named_reply(const LinkProfile& profile, const NamedReply& reply);

}  // namespace dtmf::signal
