#include "reliability/renewal_frame.h"

#include "reliability/sealed_frame.h"

namespace dtmf::reliability {

namespace {
constexpr int kSlotBits = kAddressBits + kRenewalMacBits;  // 21
constexpr WideBits mask(int bits) { return (WideBits{1} << bits) - 1; }
static_assert(kRenewalSlots * kSlotBits + kSealedCounterLowBits + kSealedCheckBits == kSealedFrameBits);
}  // namespace

FrameBits renewal_frame_pack(const RenewalFrame& f) {
  WideBits body = 0;
  for (const RenewalSlot& slot : f.slots) {
    body = body << kAddressBits | (slot.address & kAddressMask);
    body = body << kRenewalMacBits | (slot.mac & mask(kRenewalMacBits));
  }
  body = body << kSealedCounterLowBits | (f.counter_low & mask(kSealedCounterLowBits));
  return sealed_with_check(body);
}

std::optional<RenewalFrame> renewal_frame_unpack(FrameBits bits) {
  const auto checked = sealed_checked_body(bits);
  if (!checked) return std::nullopt;
  const WideBits body = *checked;
  RenewalFrame f;
  f.counter_low = static_cast<std::uint32_t>(body & mask(kSealedCounterLowBits));
  WideBits slots = body >> kSealedCounterLowBits;
  for (int i = kRenewalSlots - 1; i >= 0; --i, slots >>= kSlotBits) {
    RenewalSlot& slot = f.slots[static_cast<std::size_t>(i)];
    slot.mac = static_cast<std::uint32_t>(slots & mask(kRenewalMacBits));
    slot.address = static_cast<std::uint8_t>((slots >> kRenewalMacBits) & kAddressMask);
  }
  return f;
}

}  // namespace dtmf::reliability
