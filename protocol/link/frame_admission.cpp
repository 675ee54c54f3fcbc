#include "link/frame_admission.h"

#include <algorithm>

#include "command/command_payload.h"
#include "link/admission_verdicts.h"
#include "reliability/command_frame.h"
#include "reliability/sealed_frame.h"
#include "security/counter_clock.h"
#include "security/freshness.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

using admission::Condition;
using reading::FrameKind;

namespace {

// The reception of `heard` before anything is made of it: where and when, and its bits' tones.
Reception heard_reception(const HeardHopFrame& heard, bool sealed, const LinkProfile& profile) {
  Reception r;
  r.start_ms = heard.start_ms;
  r.heard_ms = heard.heard_ms;
  r.bits = heard.bits;
  r.intact = heard.intact;
  r.bit_count = sealed ? reliability::kSealedFrameBits : reliability::kCommandFrameBits;
  r.check_bit_count = sealed ? reliability::kSealedCheckBits : reliability::kCommandCrcBits;
  r.tones_hz = sealed ? signal::frame_tones_hz(profile, reliability::sealed_frame_symbols(heard.bits))
                      : signal::frame_tones_hz(profile, reliability::command_frame_symbols(heard.bits.low64()));
  return r;
}

// A sealed command's or synchronisation's counter against the last accepted and this robot's
// clock (security/freshness.h): Ahead before anything else, and AheadStop for a Stop, which
// is never refused for its time.
Condition counter_condition(std::uint64_t last, std::uint64_t counter, std::uint64_t clock, bool stop) {
  switch (security::freshness_of(last, counter, clock)) {
    case security::Freshness::Ahead:
      return stop ? Condition::AheadStop : Condition::Ahead;
    case security::Freshness::Stale:
      return Condition::Stale;
    case security::Freshness::Repeat:
      return Condition::Repeat;
    case security::Freshness::New:
      break;
  }
  return Condition::Fresh;
}

// Why a sealed frame of this robot's counter was not taken (Ahead, Stale) or not again (Repeat).
std::string counter_words(Condition condition, std::uint64_t counter, std::uint64_t last, std::uint64_t clock) {
  switch (condition) {
    case Condition::Ahead:
      return "counter " + std::to_string(counter) + " lies " + admission::ahead_of_clock_words(counter, clock) +
             ": not taken nor kept. Is the sender's clock fast, or this robot's slow? Set both by NTP";
    case Condition::Stale:
      return "counter " + std::to_string(counter) + " is older than the last accepted, " + std::to_string(last) +
             ": a frame captured and played again";
    case Condition::Repeat:
      return "repeat of counter " + std::to_string(counter) + ", not executed again";
    default:
      return {};
  }
}

}  // namespace

std::string admission::ahead_of_clock_words(std::uint64_t counter, std::uint64_t clock_counter) {
  const double ahead_s = static_cast<double>(counter - std::min(counter, clock_counter)) / security::kCountersPerSecond;
  return std::to_string(static_cast<long long>(ahead_s)) +
         " s ahead of this robot's clock (the margin: " + std::to_string(security::kClockMarginS) + " s)";
}

security::FrameMacInput sealed_mac_input(const Reception& r) {
  const auto f = reliability::sealed_frame_unpack(r.bits);
  return f && r.counter ? reading::sealed_mac_input(*f, *r.counter, r.mac_payload) : security::FrameMacInput{};
}

FrameAdmission::FrameAdmission(const LinkProfile& profile, const LinkOptions& options)
    : profile_(profile),
      options_(options),
      // Within this, the sender cannot have sent 15 new frames: no sequence number comes round.
      echoes_(static_cast<double>(reliability::EchoMemory::kFramesRemembered) * 1000.0 *
              profile.hops().frame_samples() / profile.sample_rate_hz) {
  if (options_.room_key) room_.emplace(options_.room_counters->last_accepted());
}

// Read once, then judged once: the reading settles what the frame is (its MACs verified), the
// rules what becomes of it.
std::optional<Reception> FrameAdmission::admit(const HeardHopFrame& heard) {
  const bool sealed = heard.chords == profile_.hops().sealed_chords_per_frame;
  Reception r = heard_reception(heard, sealed, profile_);
  const reading::FrameReading frame = reading::read_frame(heard, sealed, reading_context());
  const Rule& rule = std::visit([&](const auto& kind) -> const Rule& { return act(kind, r); }, frame);
  if (rule.verdict == admission::Verdict::Unheard) return std::nullopt;
  return r;
}

reading::ReadingContext FrameAdmission::reading_context() const {
  reading::ReadingContext c;
  c.address = options_.address;
  c.key = options_.key.get();
  c.room_key = options_.room_key.get();
  c.last_accepted = options_.key ? options_.counters->last_accepted() : 0;
  if (renewable_ && renewable_->sealed) c.renewable_counter = renewable_->counter;
  c.echoes = &echoes_;
  return c;
}

bool FrameAdmission::authentic(const reliability::FrameBits& bits) const {
  const auto frame = reliability::sealed_frame_unpack(bits);
  return frame && reading::verify_sealed(*frame, bits, reading_context()).any();
}

std::uint64_t FrameAdmission::clock_counter() const { return security::clock_counter_floor(options_.wall_clock()); }

const admission::Rule& FrameAdmission::judge(FrameKind kind, Condition condition, Reception& r) const {
  const Rule& rule = admission::admission_rule(kind, condition);
  r.event = admission::event_of(rule.verdict);
  r.refusal = rule.refusal;
  r.answered = rule.answered;
  r.authenticated = rule.authenticated;
  if (&rule == &admission::kUnlisted)
    r.detail = "no rule for a " + std::string(reading::kind_name(kind)) + " frame that is " +
               std::string(admission::condition_name(condition)) + ": refused";
  return rule;
}

// Broken: NACKed where its address reads as this robot's. Another robot's damaged frame is
// not this one's to complain about: its NACK would sound over that robot's ACK.
const admission::Rule& FrameAdmission::act(const reading::Broken& frame, Reception& r) {
  return judge(FrameKind::Broken, frame.addressed_here ? Condition::AddressedHere : Condition::AddressedElsewhere, r);
}

// The room's, not the sender's: not ours to answer.
const admission::Rule& FrameAdmission::act(const reading::Echo&, Reception& r) {
  ++echoes_ignored_;
  return judge(FrameKind::Echo, Condition::Always, r);
}

const admission::Rule& FrameAdmission::act(const reading::Elsewhere&, Reception& r) {
  return judge(FrameKind::Elsewhere, Condition::Always, r);
}

const admission::Rule& FrameAdmission::act(const reading::PlainCommand& frame, Reception& r) {
  r.sequence = frame.frame.sequence;
  const Condition condition = plain_refused()                    ? Condition::KeyedRobot
                              : !frame.decoded.command           ? Condition::Undecodable
                              : sequence_.is_repeat(frame.frame) ? Condition::Repeat
                                                                 : Condition::Fresh;
  const Rule& rule = judge(FrameKind::PlainCommand, condition, r);
  switch (condition) {
    case Condition::KeyedRobot:
      r.detail =
          "an unauthenticated frame, and this robot has a key (dtmf-agent --accept-unauthenticated lets them in)";
      break;
    case Condition::Undecodable:  // passed the checks by chance, or a kind this robot lacks
      r.detail = frame.decoded.error;
      break;
    case Condition::Repeat:  // a retransmission after a lost ACK
      r.detail = "repeat, not executed again";
      break;
    case Condition::Fresh:
      sequence_.first_time(frame.frame);
      take_command(r, *frame.decoded.command);
      hold_renewable(r, *frame.decoded.command, frame.frame.sequence, false);
      break;
    default:
      break;
  }
  return rule;
}

const admission::Rule& FrameAdmission::act(const reading::Synchronisation& frame, Reception& r) {
  r.counter = frame.counter;
  r.mac_payload = reading::kSyncPayload;
  const std::uint64_t last = options_.counters->last_accepted();
  const std::uint64_t clock = clock_counter();
  const Condition condition = counter_condition(last, frame.counter, clock, false);
  const Rule& rule = judge(FrameKind::Synchronisation, condition, r);
  if (rule.keeps_counter) options_.counters->accept(frame.counter);  // kept before it is answered
  r.detail = counter_words(condition, frame.counter, last, clock);
  if (condition == Condition::Fresh) {
    echoes_.remember(r.bits, r.heard_ms);
    r.detail = "counter synchronised at " + std::to_string(frame.counter);
  }
  return rule;
}

const admission::Rule& FrameAdmission::act(const reading::SealedCommand& frame, Reception& r) {
  r.counter = frame.counter;
  r.mac_payload = frame.payload;
  const std::uint64_t last = options_.counters->last_accepted();
  const std::uint64_t clock = clock_counter();
  const auto& command = frame.decoded.command;
  Condition condition =
      counter_condition(last, frame.counter, clock, command && std::holds_alternative<command::Stop>(*command));
  if (condition == Condition::Fresh && !command) condition = Condition::Undecodable;
  const Rule& rule = judge(FrameKind::SealedCommand, condition, r);
  if (rule.keeps_counter) options_.counters->accept(frame.counter);  // kept before the frame acts or is answered
  r.detail = counter_words(condition, frame.counter, last, clock);
  switch (condition) {
    case Condition::AheadStop:  // a sender whose clock runs fast (or this robot's slow): refusing would leave it
                                // driving, and the counter, not kept, cannot make the true frames after it look old
      take_command(r, *command);
      r.detail += "; counter " + std::to_string(frame.counter) + " lies " +
                  admission::ahead_of_clock_words(frame.counter, clock) +
                  ": stopped, the counter not kept (is the sender's clock fast, or this robot's slow?)";
      break;
    case Condition::Undecodable:
      r.detail = frame.decoded.error;
      break;
    case Condition::Fresh:
      take_command(r, *command);
      if (frame.form == reliability::SealedForm::Sync) r.detail += " (its whole counter carried: in step from here)";
      hold_renewable(r, *command, frame.counter, true);
      break;
    default:
      break;
  }
  return rule;
}

// A frame this robot cannot check may be another robot's (its own key, or none): refused
// here, and left for that robot to answer.
const admission::Rule& FrameAdmission::act(const reading::Unverified& frame, Reception& r) {
  r.counter = frame.counter;
  const Rule& rule = judge(FrameKind::Unverified, frame.counter ? Condition::MacFails : Condition::NoKey, r);
  r.detail = frame.counter ? "its MAC fails for counter " + std::to_string(*frame.counter) +
                                 ": forged, captured before the last frame accepted, or made under another key"
                           : "an authenticated frame, and this robot has no key (dtmf-agent --key)";
  return rule;
}

void FrameAdmission::take_command(Reception& r, const command::Command& command) {
  renewable_.reset();  // a renewal renews the velocity taken last, and only while nothing came after it
  echoes_.remember(r.bits, r.heard_ms);
  r.command = command;
  r.detail = command::describe(*r.command);
}

void FrameAdmission::hold_renewable(const Reception& r, const command::Command& command, std::uint64_t id,
                                    bool sealed) {
  if (const auto* velocity = std::get_if<command::Velocity>(&command))
    renewable_ = Renewable{id, *velocity, r.start_ms, admission::lease_end(*velocity, r.start_ms), {}, sealed};
}

}  // namespace dtmf::link
