// FrameAdmission's joint renewals (frame_admission.h): a keyed renewal, read where this
// robot's slot holds for the renewal's counter and the velocity taken last; a plain one from
// the slot that names the plain velocity's number. Either renews that velocity's lease, never
// answered, within kRenewalHorizonMs of its frame and while its lease still runs. Their rows:
// admission_rules.h.
#include "link/admission_verdicts.h"
#include "link/frame_admission.h"

namespace dtmf::link {

using admission::Condition;
using reading::FrameKind;

const admission::Rule& FrameAdmission::act(const reading::PlainRenewal& frame, Reception& r) {
  r.sequence = frame.slot.sequence;
  // Only a plain velocity: a plain renewal of a sealed one would let anyone keep a keyed robot moving.
  const bool renewable = renewable_ && !renewable_->sealed && renewable_->counter == frame.slot.sequence;
  const Condition condition = plain_refused() ? Condition::KeyedRobot
                              : !renewable    ? Condition::NotRenewable
                                              : renewal_condition(r.start_ms, frame.renewal.number);
  const Rule& rule = judge(FrameKind::PlainRenewal, condition, r);  // up to three robots heard it: no answers
  switch (condition) {
    case Condition::KeyedRobot:
      r.detail =
          "an unauthenticated renewal, and this robot has a key (dtmf-agent --accept-unauthenticated lets them in)";
      break;
    case Condition::NotRenewable:
      r.detail = "a renewal of the velocity frame numbered " + std::to_string(frame.slot.sequence) +
                 ", not the velocity this robot took last (it missed that frame or took a command since): renews "
                 "nothing";
      break;
    default:  // past the horizon: not what its sender sends (it sends the velocity again every 5 s)
      renew(condition, r, frame.renewal.number,
            "renewal " + std::to_string(frame.renewal.number) + " of the velocity numbered " +
                std::to_string(frame.slot.sequence));
      break;
  }
  return rule;
}

const admission::Rule& FrameAdmission::act(const reading::JointRenewal& frame, Reception& r) {
  r.counter = frame.counter;
  // A sender numbers a renewal after the velocity it renews.
  const Condition condition = frame.counter == renewable_->counter ? Condition::NumberedAsRenewed
                                                                   : renewal_condition(r.start_ms, frame.counter);
  const Rule& rule = judge(FrameKind::JointRenewal, condition, r);  // up to three robots heard it: no answers
  if (condition == Condition::NumberedAsRenewed)
    r.detail = "a renewal numbered as the velocity it renews (counter " + std::to_string(frame.counter) + "): forged";
  else
    renew(condition, r, frame.counter, "renewal of the velocity of counter " + std::to_string(renewable_->counter));
  return rule;
}

admission::Condition FrameAdmission::renewal_condition(double start_ms, std::uint64_t id) const {
  if (start_ms - renewable_->start_ms > kRenewalHorizonMs) return Condition::PastHorizon;
  if (start_ms > renewable_->lease_ends_ms) return Condition::LeaseEnded;
  if (renewable_->renewed.contains(id)) return Condition::Repeat;  // its echo, or played again: renewed already
  return Condition::Fresh;
}

void FrameAdmission::renew(Condition condition, Reception& r, std::uint64_t id, const std::string& what) {
  switch (condition) {
    case Condition::PastHorizon:
      r.detail = "a " + what + ", " + std::to_string(static_cast<int>((r.start_ms - renewable_->start_ms) / 1000)) +
                 " s after it, past the " + std::to_string(static_cast<int>(kRenewalHorizonMs / 1000)) +
                 " s a velocity is renewed for: renewals captured and played later";
      break;
    case Condition::LeaseEnded:
      r.detail = "a " + what + ", " + std::to_string(static_cast<int>(r.start_ms - renewable_->lease_ends_ms)) +
                 " ms after the velocity's lease ran out: the robot stopped, and only a new velocity frame drives it "
                 "again";
      break;
    case Condition::Repeat:
      r.detail = "repeat of " + what + ", not executed again";
      break;
    case Condition::Fresh:
      renewable_->renewed.insert(id);
      echoes_.remember(r.bits, r.heard_ms);
      renewable_->lease_ends_ms = admission::lease_end(renewable_->velocity, r.start_ms);
      r.command = renewable_->velocity;
      r.detail = what + ": " + command::describe(*r.command);
      break;
    default:
      break;
  }
}

}  // namespace dtmf::link
