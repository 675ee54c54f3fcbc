// Reliability layer: the fast profile's replies as a code — one tone index (0..3) in each of
// the reply's twelve bands (two chords of six, signal/hop_reply.h).
//
// Named replies: ACK naming a frame's sequence number (0..15), or NACK. They are 17 fixed
// words any two of which differ in at least 7 of the 12 tones, so a reply with up to three
// tones lost or misread (a fade, a click, a drowned tone) is still told from every other: a
// reading names the reply that `tones_needed` (9) or more of its tones agree with.
// Tagged ACKs: the ACK to an authenticated frame spells its tag (security/frame_mac.h: a MAC
// over the frame's MAC under the key) reduced to kReplyTagSpace = 4^6 * 3^6 values (21.5
// bits): the first chord's six tones in base 4, the second's as offsets 1..3 from the first
// chord's tone of the same band. The sender knows the tag it waits for, so it does not decode
// tags: a reading answers the frame when `kTagTonesNeeded` (11) of its tones are heard and
// not one is wrong (in a room one tone of twelve is now and then drowned in a notch). A
// reading with that many tones heard that does not spell the tag is a guess, and the sender
// takes at most `kTagGuessesPerAttempt` per transmission: a sender that does not hold the key
// has one chance in 995 328 a guess (one tone left out: 4^6 * 3^5), docs/security.md has what
// that means per frame and per hour.
// No reply repeats a band's tone from its first chord in its second: in a room the first
// chord's tone rings on into the second, and the listener never takes it for a second-chord
// tone (signal/hop_reply.h). Pure logic.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace dtmf::reliability {

inline constexpr int kReplyTones = 12;
inline constexpr int kReplyBandsPerChord = kReplyTones / 2;
inline constexpr int kReplyToneValues = 4;
inline constexpr std::uint32_t kReplyTagSpace = 4u * 4 * 4 * 4 * 4 * 4 * 3 * 3 * 3 * 3 * 3 * 3;  // 2 985 984
inline constexpr int kTagTonesNeeded = 11;
// Readings of 11 or more tones that do not spell the tag, per transmission: in the measured
// rooms with the sender's own frames 20 dB over the answer, an answer came after at most 9
// (bench/frames/rooms.cpp, the answer-path case).
inline constexpr int kTagGuessesPerAttempt = 16;

struct NamedReply {
  bool ack = false;
  std::uint8_t sequence = 0;  // ACK only
  bool operator==(const NamedReply&) const = default;
};

using ReplyTones = std::array<std::uint8_t, kReplyTones>;
// A reading: each band's tone, or -1 where the band was not heard.
using ReplyReading = std::array<int, kReplyTones>;

// What the ear heard of a reply, for a sender that knows which tag it waits for: the plain
// reading, and each band's second-chord tone read again with each possible first-chord tone
// set aside. The first chord's tone rings on into the second, and where the reverberation
// outweighs the direct sound (the smoking room: 13 dB) its tail can stand over the second
// chord's own tone; the plain reading sets aside the first-chord tone it heard, which misses
// when that tone was not heard. Setting aside the tag's own first-chord tone tells a forger
// nothing: a second-chord tone is never it.
struct TagEvidence {
  ReplyReading plain{};
  std::array<std::array<std::int8_t, kReplyToneValues>, kReplyBandsPerChord> second_beside{};  // [band][first]
  bool operator==(const TagEvidence&) const = default;
};

ReplyTones reply_codeword(const NamedReply& reply);
// The named reply that at least `tones_needed` of the reading's tones agree with, or nothing.
std::optional<NamedReply> read_reply(const ReplyReading& reading, int tones_needed);

// The tones of a tagged ACK spelling `tag` (< kReplyTagSpace).
ReplyTones tag_tones(std::uint32_t tag);
// The tag a reading spells when every tone was heard and none repeats its band's first tone
// (dtmfctl decode shows it).
std::optional<std::uint32_t> read_tag(const ReplyReading& reading);
// Tones of the reading that were heard.
int heard_tones(const ReplyReading& reading);
// Whether the reading spells `tag`: kTagTonesNeeded tones or more heard, and all of them agree.
bool spells_tag(const ReplyReading& reading, std::uint32_t tag);
// The reading of `evidence` for a sender waiting for `tag`: the second chord read with the
// tag's own first-chord tones set aside.
ReplyReading reading_for(const TagEvidence& evidence, std::uint32_t tag);
// Whether the evidence, read for `tag`, spells it.
bool spells_tag(const TagEvidence& evidence, std::uint32_t tag);

}  // namespace dtmf::reliability
