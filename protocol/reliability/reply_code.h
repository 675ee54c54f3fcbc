// Reliability layer: the fast profile's replies as a code — ACK naming a frame's sequence
// number (0..15), or NACK — spelt as one tone index (0..7) in each of four reply bands.
//
// The 17 replies are codewords of RS(4, 2) over GF(8): any two differ in at least three of
// the four bands, so a reply with one band lost (a fade in a room, a drowned tone) is still
// told from every other, and a reply is read when `bands_needed` bands agree with it.
// Codewords with a tone 0 in any band are not used: tone 0 of the four bands are 2000,
// 2500, 3000 and 3500 Hz, the seed profile's ACK and NACK tones, and a fast reply must never
// sound like a seed answer (signal/hop_reply.h). Pure logic.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace dtmf::reliability {

struct NamedReply {
  bool ack = false;
  std::uint8_t sequence = 0;  // ACK only
  bool operator==(const NamedReply&) const = default;
};

using ReplyTones = std::array<std::uint8_t, 4>;

ReplyTones reply_codeword(const NamedReply& reply);

// The reply that at least `bands_needed` of the bands' tones agree with (a tone of -1: that
// band was not heard), or nothing.
std::optional<NamedReply> read_reply(const std::array<int, 4>& tones, int bands_needed);

}  // namespace dtmf::reliability
