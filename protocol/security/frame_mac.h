// Security layer: the truncated MAC of an authenticated frame and the tag of its answer, in
// the spirit of AUTOSAR SecOC (a truncated MAC over the data and a freshness value).
//
// Both are keyed BLAKE2b (libsodium's crypto_generichash, a 128-bit output) over one fixed
// byte string: a frame's MAC truncated to its first 32 bits, an answer's tag all 128 (a byte
// for each of the 16 tones of a tagged ACK: reliability/tag_chord.h):
//   "dtmf-teleop/1" | direction (1 byte) | key id (4) | address (1) | form (1) | counter (8) | body (4)
// The direction keeps a frame's MAC from ever serving as an answer's tag and back; the key id
// and the robot's address bind it to one key and one robot; the counter is the full freshness
// value, of which a frame carries only the low bits; the body is the command's payload (a
// frame) or the MAC of the frame answered (an answer's tag). Pure: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>

#include "security/link_key.h"

namespace dtmf::security {

enum class Direction : std::uint8_t { ToRobot = 1, ToSender = 2 };

// What a frame's MAC covers.
struct FrameMacInput {
  std::uint8_t address = 0;  // the robot the frame is for (0..7)
  std::uint8_t form = 0;     // the frame's form (a command, or a counter synchronisation)
  std::uint64_t counter = 0;
  std::uint32_t payload = 0;  // the command; 0 for a synchronisation
  bool operator==(const FrameMacInput&) const = default;
};

std::uint32_t frame_mac(const LinkKey& key, const FrameMacInput& input);

// A joint renewal's slot (reliability/renewal_frame.h) is a MAC under the renewed robot's own
// key over form 2 (a frame's forms are 0 and 1, so no slot is ever a frame's MAC), the
// renewal's full counter and, as the body, the low 32 bits of the counter of the velocity
// frame it renews: it renews that velocity and no other. The frame carries its leading bits.
inline constexpr std::uint8_t kRenewalForm = 2;
inline FrameMacInput renewal_mac_input(std::uint8_t address, std::uint64_t counter, std::uint64_t renewed_counter) {
  return {address, kRenewalForm, counter, static_cast<std::uint32_t>(renewed_counter)};
}

inline constexpr std::size_t kAnswerTagBytes = 16;
using AnswerTag = std::array<std::uint8_t, kAnswerTagBytes>;

// The tag of the robot's ACK to the frame whose MAC input and MAC are given: only a holder of
// the key can make it, and it answers that one frame.
AnswerTag answer_tag(const LinkKey& key, const FrameMacInput& frame, std::uint32_t frame_mac);

}  // namespace dtmf::security
