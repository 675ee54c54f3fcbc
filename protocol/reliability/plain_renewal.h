// Reliability layer: the fast profile's joint renewal without keys — one 50-bit frame that
// renews the leases of up to three robots' velocities at once (docs/protocol.md §10,
// "Renewing leases together"), as renewal_frame.h does for keyed robots.
//
// It is a command frame (command_frame.h) whose payload has the reserved kind 7 (EXTENDED)
// and the sub-kind RENEWAL; its address and sequence fields carry the renewal's number:
//
//   bits 49..43  the renewal's number, 7 bits: new for every renewal its sender sends
//   bits 42..40  payload kind 7 (EXTENDED)
//   bits 39..37  sub-kind 1 (RENEWAL)
//   bits 36..30  slot 0: the robot's address (3 bits), the sequence number of the velocity
//                frame it renews (4 bits)
//   bits 29..23  slot 1
//   bits 22..16  slot 2 (a slot nobody needs repeats slot 0)
//   bits 15..0   CRC-16, as every command frame's
//
// Why a number of its own: renewals of one velocity would otherwise have the same bits, and
// the robot could not tell the next renewal from the room's echo of the last (which would
// stretch a lease past the sender's last word). Why a velocity's sequence number: a renewal
// renews the velocity the robot took last only if its sender meant that one, so a robot that
// missed the newest velocity keeps nothing. Pure logic: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "reliability/command_frame.h"

namespace dtmf::reliability {

inline constexpr int kPlainRenewalSlots = 3;
inline constexpr int kPlainRenewalNumberBits = kAddressBits + kSequenceBits;  // 7
inline constexpr std::uint32_t kPlainRenewalNumberMask = (1u << kPlainRenewalNumberBits) - 1;

struct PlainRenewalSlot {
  std::uint8_t address = 0;   // the robot renewed (0..7)
  std::uint8_t sequence = 0;  // the sequence number of the velocity frame it renews (0..15)
  bool operator==(const PlainRenewalSlot&) const = default;
};

struct PlainRenewal {
  std::uint32_t number = 0;  // 7 bits
  std::array<PlainRenewalSlot, kPlainRenewalSlots> slots{};
  bool operator==(const PlainRenewal&) const = default;
};

CommandFrame plain_renewal_pack(const PlainRenewal& renewal);
// The renewal `frame` is, if its payload is one (any other payload is a command or nothing).
std::optional<PlainRenewal> plain_renewal_unpack(const CommandFrame& frame);

}  // namespace dtmf::reliability
