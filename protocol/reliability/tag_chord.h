// Reliability layer: the ACK to an authenticated frame as one chord of sixteen 32-ary tones
// that spell its tag, and the check of a reading against the tag a sender waits for.
//
// The tag (security/frame_mac.h: a 128-bit MAC under the key over the frame answered) gives
// each band k a byte, which picks one of the values that band has free: the frame's own tones
// there and the bins beside them are taken (tag_chord_taken), since the sender's microphone
// hears its own frame ring in them when the answer comes. Tone k sounds in band k of the
// frame's sixteen bands (both band sets at once: signal/hop_synthesizer.h). The sender does not
// decode tags: it knows the one it waits for and counts the bands whose reading (the most risen
// tone not taken) is that tag's symbol. A reading answers the frame when
// kTagChordMatchesNeeded (9) of the 16 agree, whatever the others read: in a room a tone now
// and then drowns in a notch or under a tail, and 7 of 16 may. A band has at least 26 free
// values, so a stranger's sound matches it at most 10 times in 256 (the byte mod 26), and a
// reading of random tones answers with a chance of at most sum_{k>=9} C(16,k) p^k (1-p)^(16-k)
// = 1.9e-9 (p = 10/256), for each of kTagChordHypotheses frequency offsets the ear reads at:
// 9.4e-9 a reading, one reading per 10.25 ms hop, at most 3.3e-3 an hour with no budget, so
// a forger's guesses never silence the true answer (docs/security.md). What the frame sent is
// public, so taking its bins tells a forger nothing. Pure logic.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace dtmf::reliability {

inline constexpr int kTagChordTones = 16;
inline constexpr int kTagChordValues = 32;
inline constexpr int kTagChordMatchesNeeded = 9;
inline constexpr int kTagChordHypotheses = 5;  // frequency offsets read (profile/link_profile.h)
// A band's risen tones handed over, the most risen first: the frame's own tones and their
// neighbours (up to 6 values, set aside) may rise too, and 3 more keep its most risen free one.
inline constexpr int kTagChordCandidates = 9;
inline constexpr int kTagBytes = kTagChordTones;  // a byte per tone

using TagBytes = std::array<std::uint8_t, kTagBytes>;
using TagChordSymbols = std::array<std::uint8_t, kTagChordTones>;
// Per band, a bit for each value (1 << v): what the sender sent in that band.
using BandValueSet = std::array<std::uint32_t, kTagChordTones>;
// What the ear heard: [hypothesis][band][rank], a tone value or -1.
using TagChordReading =
    std::array<std::array<std::array<std::int8_t, kTagChordCandidates>, kTagChordTones>, kTagChordHypotheses>;

// The tones the frame answered sent in each band, and the bins beside them: its tail rings
// there at the sender's microphone. `frame_symbols`: eight per chord, chords alternating
// between the two band sets (signal/hop_synthesizer.h).
BandValueSet tag_chord_taken(std::span<const std::uint8_t> frame_symbols);
// The tag's symbols: band k's byte picks one of the values `taken` leaves free in band k
// (byte mod their count, in order), so the robot never answers where the sender's own frame
// rings and no band of a tag is lost to it.
TagChordSymbols tag_chord_symbols(const TagBytes& tag, const BandValueSet& taken);
// The bands of the best hypothesis whose reading, with `set_aside` put aside, is the tag's symbol.
int tag_chord_matches(const TagChordReading& reading, const TagChordSymbols& tag, const BandValueSet& set_aside);
// Whether the reading answers the frame whose tag is `tag`.
bool spells_tag_chord(const TagChordReading& reading, const TagChordSymbols& tag, const BandValueSet& set_aside);
// The bands any hypothesis heard (for gates and people).
int tag_chord_heard(const TagChordReading& reading);
// Each band's reading at the hypothesis that heard most, nothing set aside: for people and
// tools (dtmfctl decode), which have no tag to wait for.
std::array<int, kTagChordTones> tag_chord_plain(const TagChordReading& reading);

}  // namespace dtmf::reliability
