// FrameAdmission's joint renewals (frame_admission.h): a keyed renewal taken from the slot
// that names this robot and whose MAC holds for the renewal's counter and the velocity taken
// last; a plain one from the slot that names the plain velocity's number. Either renews that
// velocity's lease, never answered, within kRenewalHorizonMs of its frame and while its lease
// still runs.
#include <algorithm>

#include "link/admission_verdicts.h"
#include "link/frame_admission.h"
#include "reliability/renewal_frame.h"
#include "security/frame_mac.h"
#include "security/freshness.h"

namespace dtmf::link {

using admission::refuse;
using admission::refuse_unchecked;

std::optional<Reception> FrameAdmission::admit_plain_renewal(Reception r, const reliability::PlainRenewal& renewal) {
  const auto slot = std::find_if(renewal.slots.begin(), renewal.slots.end(),
                                 [&](const reliability::PlainRenewalSlot& s) { return s.address == options_.address; });
  if (slot == renewal.slots.end()) return std::nullopt;  // other robots' renewal
  r.answered = false;                                    // up to three robots heard it: answers would sound together
  r.sequence = slot->sequence;
  if (options_.key && !options_.accept_unauthenticated) {
    refuse_unchecked(
        r, "an unauthenticated renewal, and this robot has a key (dtmf-agent --accept-unauthenticated lets them in)");
    return r;
  }
  // Only a plain velocity: a plain renewal of a sealed one would let anyone keep a keyed robot moving.
  if (!renewable_ || renewable_->sealed || renewable_->counter != slot->sequence) {
    r.event = ReceptionEvent::Ignored;
    r.detail = "a renewal of the velocity frame numbered " + std::to_string(slot->sequence) +
               ", not the velocity this robot took last (it missed that frame or took a command since): renews nothing";
    return r;
  }
  // Past the horizon: not what its sender sends (it sends the velocity again every 5 s).
  take_renewal(
      r, renewal.number,
      "renewal " + std::to_string(renewal.number) + " of the velocity numbered " + std::to_string(slot->sequence),
      RefusalReason::Payload);
  return r;
}

std::optional<std::uint64_t> FrameAdmission::renewal_counter(const reliability::FrameBits& bits) const {
  if (!options_.key || !renewable_ || !renewable_->sealed) return std::nullopt;
  const auto renewal = reliability::renewal_frame_unpack(bits);
  if (!renewal) return std::nullopt;
  const std::uint64_t counter = security::complete_counter(renewable_->counter, renewal->counter_low);
  const std::uint32_t mac =
      security::frame_mac(*options_.key, security::renewal_mac_input(options_.address, counter, renewable_->counter)) >>
      (32 - reliability::kRenewalMacBits);
  for (const reliability::RenewalSlot& slot : renewal->slots) {
    if (slot.address == options_.address && slot.mac == mac) return counter;
  }
  return std::nullopt;
}

bool FrameAdmission::admit_renewal(Reception& r) {
  const auto counter = renewal_counter(r.bits);
  if (!counter) return false;
  r.answered = false;  // up to three robots heard it: answers would sound together
  r.counter = *counter;
  if (*counter == renewable_->counter) {  // a sender numbers a renewal after the velocity it renews
    refuse(r, RefusalReason::Authentication,
           "a renewal numbered as the velocity it renews (counter " + std::to_string(*counter) + "): forged");
    return true;
  }
  if (take_renewal(r, *counter, "renewal of the velocity of counter " + std::to_string(renewable_->counter),
                   RefusalReason::Authentication))
    r.authenticated = true;
  return true;
}

bool FrameAdmission::take_renewal(Reception& r, std::uint64_t id, const std::string& what, RefusalReason late) {
  if (r.start_ms - renewable_->start_ms > kRenewalHorizonMs) {
    refuse(r, late,
           "a " + what + ", " + std::to_string(static_cast<int>((r.start_ms - renewable_->start_ms) / 1000)) +
               " s after it, past the " + std::to_string(static_cast<int>(kRenewalHorizonMs / 1000)) +
               " s a velocity is renewed for: renewals captured and played later");
    return false;
  }
  if (r.start_ms > renewable_->lease_ends_ms) {
    refuse(r, late,
           "a " + what + ", " + std::to_string(static_cast<int>(r.start_ms - renewable_->lease_ends_ms)) +
               " ms after the velocity's lease ran out: the robot stopped, and only a new velocity frame drives it "
               "again");
    return false;
  }
  if (!renewable_->renewed.insert(id).second) {  // its echo, or played again: renewed already
    r.event = ReceptionEvent::Repeat;
    r.detail = "repeat of " + what + ", not executed again";
    return true;
  }
  echoes_.remember(r.bits, r.heard_ms);
  renewable_->lease_ends_ms = admission::lease_end(renewable_->velocity, r.start_ms);
  r.command = renewable_->velocity;
  r.event = ReceptionEvent::Renewed;
  r.detail = what + ": " + command::describe(*r.command);
  return true;
}

}  // namespace dtmf::link
