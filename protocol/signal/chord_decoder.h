// Signal layer: from the peaks of one window to a chord, or to nothing.
//
// Robot side: a command chord is accepted only when the peaks that match plan tones give
// one tone in each of the four bands that stands `dominance_db` above any other plan tone
// of its band — a missing band or two tones of like level in one band (two chords at once,
// or a strong interferer on a plan tone) mean no chord, while a noise peak far below the
// chord does not (DTMF receivers judge tones by their relative level the same way, e.g.
// spandsp's 8 dB "relative peak" tests). Peaks that match no plan tone are ignored, as the
// seed does, unless `crowding_peaks` of them are as loud as the chord's weakest tone: then
// the window holds something else (the fast profile's sixteen-tone chords, music).
// A common frequency offset (Doppler, two sound cards' clocks) moves every tone by the same
// factor; the factor within `max_offset_ppm` under which the peaks sit closest to plan
// tones is found first, and the peaks are read through it.
// Sender side: an ACK (NACK) is accepted when both of its tones are among the peaks and
// each tone of the other reply is absent or `dominance_db` below.
// Either way the match carries its level: the amplitude of its weakest tone.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "profile/link_profile.h"
#include "signal/peak_detector.h"
#include "signal/tone_plan.h"

namespace dtmf::signal {

struct ChordMatch {
  std::uint16_t frame;
  double level;
  double offset_ppm;  // the common frequency offset the chord was read through
};

struct ReplyMatch {
  Reply reply;
  double level;
};

std::optional<ChordMatch> decode_chord(const TonePlan& plan, std::span<const Peak> peaks, const DetectorParams& rules);

std::optional<ReplyMatch> decode_reply(const TonePlan& plan, std::span<const Peak> peaks, double tolerance_hz,
                                       double dominance_db);

}  // namespace dtmf::signal
