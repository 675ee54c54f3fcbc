// The robot's rules for a frame once read (link/frame_reading.h): for each kind of frame and
// the condition that holds of it, what becomes of it — one row each in kAdmissionRules.
//
// How: FrameAdmission (frame_admission.cpp, room_stop_admission.cpp, renewal_admission.cpp)
// finds the one condition of a frame's kind, in the order that kind asks them, looks its row
// up here, and does what the row says: the event, the refusal's reason, whether it answers,
// whether the frame counts as authenticated, whether its counter is kept before it acts. What
// each row does besides (the command executed, the words logged) is the admission's.
// Why a table: the rules (frame_admission.h's header is their spec) are read and tested row
// by row (tests/link/admission_rules_test.cpp), not traced through branches.
// Header-only, constexpr: no I/O, no clock.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "link/frame_reading.h"
#include "link/reception.h"

namespace dtmf::link::admission {

using reading::FrameKind;

// What holds of a frame of a kind: the first its kind asks that holds.
enum class Condition : std::uint8_t {
  Always,              // nothing more is asked (an echo, another robot's frame)
  AddressedHere,       // a broken frame whose address reads as this robot's
  AddressedElsewhere,  // ... as another robot's
  KeyedRobot,          // a plain frame, and this robot has a key and does not let plain ones in
  RoomKeyHeld,         // a plain stop for every robot, and this robot holds the room key
  NoKey,               // a sealed frame, and this robot has no key to check it
  MacFails,            // a sealed frame whose MAC fails at the counter completed
  NotRenewable,        // a plain renewal of a velocity other than the plain one taken last
  NumberedAsRenewed,   // a joint renewal numbered as the velocity it renews: forged
  PastHorizon,         // a renewal beginning kRenewalHorizonMs or more after its velocity's frame
  LeaseEnded,          // a renewal beginning after the velocity's lease ran out
  AheadStop,           // a Stop's counter more than kClockMarginS past this robot's clock
  Ahead,               // any other frame's
  Stale,               // a counter older than the last accepted (a room counter: than the window)
  Repeat,              // the frame (a renewal: its number) taken last, again
  Undecodable,         // new, but a payload no sender makes (a kind this robot lacks)
  Fresh,               // new, and nothing against it
};

// What becomes of the frame: its Reception's event, or no reception at all.
enum class Verdict : std::uint8_t {
  Unheard,      // no reception: nobody's business here
  Nack,         // ReceptionEvent::Broken
  Refuse,       // ReceptionEvent::Refused, for the row's reason
  Ignore,       // ReceptionEvent::Ignored
  NotAgain,     // ReceptionEvent::Repeat: not executed again
  Synchronise,  // ReceptionEvent::Synchronised
  Execute,      // ReceptionEvent::Command
  Renew,        // ReceptionEvent::Renewed
};

struct Rule {
  FrameKind kind;
  Condition condition;
  Verdict verdict;
  RefusalReason refusal;
  bool answered;       // a frame every robot heard, or one this robot cannot check, is not
  bool authenticated;  // its MAC held and it counts: Reception::authenticated
  bool keeps_counter;  // its counter is kept (on disk) before it acts or is answered
};

namespace rule_columns {
inline constexpr auto kAuth = RefusalReason::Authentication;
inline constexpr auto kPayload = RefusalReason::Payload;
inline constexpr auto kNone = RefusalReason::None;
inline constexpr bool kAnswered = true, kQuiet = false;
inline constexpr bool kAuthentic = true, kUnchecked = false;
inline constexpr bool kKept = true, kNotKept = false;
}  // namespace rule_columns

// clang-format off
inline constexpr std::array kAdmissionRules = [] {
  using enum FrameKind;
  using enum Condition;
  using enum Verdict;
  using namespace rule_columns;
  return std::array{
    //   kind             condition           verdict      reason    answered   authenticated counter
    Rule{Broken,          AddressedHere,      Nack,        kNone,    kAnswered, kUnchecked, kNotKept},
    Rule{Broken,          AddressedElsewhere, Nack,        kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{Echo,            Always,             Unheard,     kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{Elsewhere,       Always,             Unheard,     kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainCommand,    KeyedRobot,         Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainCommand,    Undecodable,        Refuse,      kPayload, kAnswered, kUnchecked, kNotKept},
    Rule{PlainCommand,    Repeat,             NotAgain,    kNone,    kAnswered, kUnchecked, kNotKept},
    Rule{PlainCommand,    Fresh,              Execute,     kNone,    kAnswered, kUnchecked, kNotKept},
    Rule{PlainRoomStop,   RoomKeyHeld,        Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRoomStop,   KeyedRobot,         Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRoomStop,   Fresh,              Execute,     kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    KeyedRobot,         Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    NotRenewable,       Ignore,      kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    PastHorizon,        Refuse,      kPayload, kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    LeaseEnded,         Refuse,      kPayload, kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    Repeat,             NotAgain,    kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{PlainRenewal,    Fresh,              Renew,       kNone,    kQuiet,    kUnchecked, kNotKept},
    Rule{RoomStop,        Stale,              Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{RoomStop,        Repeat,             NotAgain,    kNone,    kQuiet,    kAuthentic, kNotKept},
    Rule{RoomStop,        Ahead,              Execute,     kNone,    kQuiet,    kAuthentic, kNotKept},
    Rule{RoomStop,        Fresh,              Execute,     kNone,    kQuiet,    kAuthentic, kKept},
    Rule{JointRenewal,    NumberedAsRenewed,  Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{JointRenewal,    PastHorizon,        Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{JointRenewal,    LeaseEnded,         Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{JointRenewal,    Repeat,             NotAgain,    kNone,    kQuiet,    kAuthentic, kNotKept},
    Rule{JointRenewal,    Fresh,              Renew,       kNone,    kQuiet,    kAuthentic, kNotKept},
    Rule{Synchronisation, Ahead,              Refuse,      kAuth,    kAnswered, kUnchecked, kNotKept},
    Rule{Synchronisation, Stale,              Refuse,      kAuth,    kAnswered, kUnchecked, kNotKept},
    Rule{Synchronisation, Repeat,             NotAgain,    kNone,    kAnswered, kAuthentic, kNotKept},
    Rule{Synchronisation, Fresh,              Synchronise, kNone,    kAnswered, kAuthentic, kKept},
    Rule{SealedCommand,   AheadStop,          Execute,     kNone,    kAnswered, kAuthentic, kNotKept},
    Rule{SealedCommand,   Ahead,              Refuse,      kAuth,    kAnswered, kUnchecked, kNotKept},
    Rule{SealedCommand,   Stale,              Refuse,      kAuth,    kAnswered, kUnchecked, kNotKept},
    Rule{SealedCommand,   Repeat,             NotAgain,    kNone,    kAnswered, kAuthentic, kNotKept},
    Rule{SealedCommand,   Undecodable,        Refuse,      kPayload, kAnswered, kAuthentic, kKept},
    Rule{SealedCommand,   Fresh,              Execute,     kNone,    kAnswered, kAuthentic, kKept},
    Rule{Unverified,      NoKey,              Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
    Rule{Unverified,      MacFails,           Refuse,      kAuth,    kQuiet,    kUnchecked, kNotKept},
  };
}();
// clang-format on

// A pair the admission cannot reach: refused, unanswered, rather than acted on.
inline constexpr Rule kUnlisted{
    FrameKind::Unverified, Condition::Always, Verdict::Refuse, RefusalReason::Payload, false, false, false};

// The row of (`kind`, `condition`): one at most (checked below).
constexpr const Rule& admission_rule(FrameKind kind, Condition condition) {
  for (const Rule& rule : kAdmissionRules) {
    if (rule.kind == kind && rule.condition == condition) return rule;
  }
  return kUnlisted;
}

constexpr bool rows_unique() {
  for (std::size_t i = 0; i < kAdmissionRules.size(); ++i) {
    for (std::size_t j = i + 1; j < kAdmissionRules.size(); ++j) {
      if (kAdmissionRules[i].kind == kAdmissionRules[j].kind &&
          kAdmissionRules[i].condition == kAdmissionRules[j].condition)
        return false;
    }
  }
  return true;
}
static_assert(rows_unique(), "one row for each kind and condition");

// "always", "addressed_here", ...: for test names and logs.
constexpr std::string_view condition_name(Condition condition) {
  constexpr std::array<std::string_view, static_cast<std::size_t>(Condition::Fresh) + 1> kNames{
      "always",       "addressed_here", "addressed_elsewhere",
      "keyed_robot",  "room_key_held",  "no_key",
      "mac_fails",    "not_renewable",  "numbered_as_renewed",
      "past_horizon", "lease_ended",    "ahead_stop",
      "ahead",        "stale",          "repeat",
      "undecodable",  "fresh"};
  return kNames[static_cast<std::size_t>(condition)];
}

// The event a verdict gives a reception (Unheard: none, read as Broken).
constexpr ReceptionEvent event_of(Verdict verdict) {
  switch (verdict) {
    case Verdict::Refuse:
      return ReceptionEvent::Refused;
    case Verdict::Ignore:
      return ReceptionEvent::Ignored;
    case Verdict::NotAgain:
      return ReceptionEvent::Repeat;
    case Verdict::Synchronise:
      return ReceptionEvent::Synchronised;
    case Verdict::Execute:
      return ReceptionEvent::Command;
    case Verdict::Renew:
      return ReceptionEvent::Renewed;
    case Verdict::Unheard:
    case Verdict::Nack:
      break;
  }
  return ReceptionEvent::Broken;
}

}  // namespace dtmf::link::admission
