// Reliability layer: the fast profile's joint renewal — one authenticated 80-bit frame that
// renews the leases of up to three robots' velocities at once (docs/protocol.md §10,
// "Renewing leases together").
//
// It has the sealed frame's shape (sealed_frame.h: the same RS(24, 16) codeword, three chords
// and CRC-8), so the receive path hears it unchanged; what tells it apart is that a slot's MAC
// holds under the robot's own key (security/frame_mac.h, renewal_mac), never a marker:
//
//   bits 79..59  slot 0: address (3 bits), MAC (18 bits)
//   bits 58..38  slot 1
//   bits 37..17  slot 2
//   bits 16..8   the freshness counter's low 9 bits, one counter for every slot
//   bits 7..0    CRC-8/AUTOSAR of bits 79..8, as the sealed frame's
//
// Why: three keyed Teleop streams renewed one frame each (a sealed frame and its tag chord,
// about 212 ms an exchange) leave each robot 1.57 renewals a second; one frame for three
// robots, unanswered, renews all three in 153.75 ms. A slot whose robot is not renewed
// repeats another slot. Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "reliability/command_frame.h"
#include "reliability/frame_bits.h"

namespace dtmf::reliability {

inline constexpr int kRenewalSlots = 3;
inline constexpr int kRenewalMacBits = 18;

struct RenewalSlot {
  std::uint8_t address = 0;  // the robot renewed (0..7)
  std::uint32_t mac = 0;     // 18 bits under that robot's key
  bool operator==(const RenewalSlot&) const = default;
};

struct RenewalFrame {
  std::array<RenewalSlot, kRenewalSlots> slots{};
  std::uint32_t counter_low = 0;  // the freshness counter's low 9 bits
  bool operator==(const RenewalFrame&) const = default;
};

FrameBits renewal_frame_pack(const RenewalFrame& frame);
// The renewal `bits` would be when its CRC holds (any intact sealed frame reads as one: only a
// slot's MAC says whether it is).
std::optional<RenewalFrame> renewal_frame_unpack(FrameBits bits);

}  // namespace dtmf::reliability
