#include "reliability/plain_renewal.h"

#include "command/command_payload.h"

namespace dtmf::reliability {

namespace {
constexpr int kKindBits = 3;
constexpr int kSubKindBits = 3;
constexpr int kSlotBits = kAddressBits + kSequenceBits;  // 7
constexpr std::uint32_t kRenewalSubKind = 1;
constexpr std::uint32_t kHeader =
    static_cast<std::uint32_t>(command::PayloadKind::Extended) << kSubKindBits | kRenewalSubKind;
constexpr std::uint32_t kSlotMask = (1u << kSlotBits) - 1;
static_assert(kKindBits + kSubKindBits + kPlainRenewalSlots * kSlotBits == kFramePayloadBits);
}  // namespace

CommandFrame plain_renewal_pack(const PlainRenewal& r) {
  std::uint32_t payload = kHeader;
  for (const PlainRenewalSlot& slot : r.slots)
    payload = payload << kSlotBits | (slot.address & kAddressMask) << kSequenceBits | (slot.sequence & kSequenceMask);
  const std::uint32_t number = r.number & kPlainRenewalNumberMask;
  return {static_cast<std::uint8_t>(number >> kSequenceBits), static_cast<std::uint8_t>(number & kSequenceMask),
          payload};
}

std::optional<PlainRenewal> plain_renewal_unpack(const CommandFrame& frame) {
  if (frame.payload >> (kPlainRenewalSlots * kSlotBits) != kHeader) return std::nullopt;
  PlainRenewal r;
  r.number = static_cast<std::uint32_t>(frame.address) << kSequenceBits | frame.sequence;
  std::uint32_t slots = frame.payload;
  for (int i = kPlainRenewalSlots - 1; i >= 0; --i, slots >>= kSlotBits) {
    PlainRenewalSlot& slot = r.slots[static_cast<std::size_t>(i)];
    slot.sequence = static_cast<std::uint8_t>(slots & kSequenceMask);
    slot.address = static_cast<std::uint8_t>((slots >> kSequenceBits) & kAddressMask);
  }
  return r;
}

}  // namespace dtmf::reliability
