// Reliability layer: the fast profile's replies as a code — one tone index (0..3) in each of
// the reply's twelve bands (two chords of six, signal/hop_reply.h).
//
// Named replies: ACK naming a robot's address (0..7) and its frame's sequence number (0..15),
// or NACK naming the robot's address. They are 136 fixed words any two of which differ in at
// least 7 of the 12 tones, so a reply with up to three tones lost or misread (a fade, a click,
// a drowned tone) is still told from every other: a reading names the reply that
// `tones_needed` (9) or more of its tones agree with. Address 0's replies are the 17 words
// of the single-robot code, unchanged: a robot and a sender of that time still understand
// each other at the default address.
// The ACK to an authenticated frame spells its tag instead: reliability/tag_chord.h.
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

struct NamedReply {
  bool ack = false;
  std::uint8_t sequence = 0;  // ACK only
  std::uint8_t address = 0;   // the robot answering: an answer never speaks for another robot
  bool operator==(const NamedReply&) const = default;
};

using ReplyTones = std::array<std::uint8_t, kReplyTones>;
// A reading: each band's tone, or -1 where the band was not heard.
using ReplyReading = std::array<int, kReplyTones>;

ReplyTones reply_codeword(const NamedReply& reply);
// The named reply that at least `tones_needed` of the reading's tones agree with, or nothing.
std::optional<NamedReply> read_reply(const ReplyReading& reading, int tones_needed);

}  // namespace dtmf::reliability
