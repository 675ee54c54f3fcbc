// The robot's first step with a frame heard (frame_admission.h): what the frame is, read once
// into one kind (FrameReading), before anything is done with it.
//
// How: a broken frame is only its address; an intact one that equals a frame taken lately is
// an echo (reliability/echo_memory.h); a 50-bit frame is told by its payload (a stop for every
// robot, a plain joint renewal, a command) and its address; an 80-bit frame's bits say nothing
// of what it is, so every reading a MAC could decide is verified first (SealedVerification:
// a stop for every robot under the room key, a command or synchronisation under this robot's
// key, a joint renewal's slot under it), and then sealed_reading() picks one by a fixed rule.
// Why verify first: a reading is never acted on before its MAC holds (libsodium's open, then
// use), and where two MACs hold the rule decides, not the order in which they were tried.
// Pure logic: no I/O, no clock; the state it reads (counters, the velocity taken last, the
// echo memory) is given in ReadingContext.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include "command/command_payload.h"
#include "link/hop_frame_path.h"
#include "reliability/command_frame.h"
#include "reliability/echo_memory.h"
#include "reliability/plain_renewal.h"
#include "reliability/sealed_frame.h"
#include "security/frame_mac.h"
#include "security/link_key.h"

namespace dtmf::link::reading {

// Failed its check (CRC); `addressed_here`: its first bits read as this robot's address.
struct Broken {
  bool addressed_here = false;
};
// Intact, and the bits of a frame taken lately other than the newest: the room's, not a sender's.
struct Echo {};
// Another robot's frame (or a renewal with no slot for this robot): nobody's business here.
struct Elsewhere {};
// A 50-bit frame for this robot whose payload is no stop for every robot and no renewal; the
// payload as decoded (a kind this robot lacks decodes to an error).
struct PlainCommand {
  reliability::CommandFrame frame;
  command::ParameterDecode decoded;
};
// A 50-bit stop for every robot, whatever its address.
struct PlainRoomStop {
  reliability::CommandFrame frame;
};
// A 50-bit joint renewal (reliability/plain_renewal.h) and its slot naming this robot.
struct PlainRenewal {
  reliability::PlainRenewal renewal;
  reliability::PlainRenewalSlot slot;
};
// An 80-bit stop for every robot: its MAC holds under the room key; its whole counter.
struct RoomStop {
  std::uint64_t room_counter = 0;
  std::uint32_t payload = 0;  // what its MAC holds for: a stop for every robot
};
// An 80-bit joint renewal (reliability/renewal_frame.h): this robot's slot holds under its key
// for `counter`, completed from the counter of the sealed velocity taken last.
struct JointRenewal {
  std::uint64_t counter = 0;
};
// An 80-bit synchronisation for this robot: its MAC holds for payload 0 at its whole counter.
struct Synchronisation {
  std::uint64_t counter = 0;
};
// An 80-bit command for this robot whose MAC holds at `counter`: in command form, or a Stop in
// synchronisation form (its MAC over STOP, its whole counter carried).
struct SealedCommand {
  reliability::SealedForm form = reliability::SealedForm::Command;
  std::uint64_t counter = 0;
  std::uint32_t payload = 0;  // what the MAC holds for
  command::ParameterDecode decoded;
};
// An 80-bit frame addressed to this robot that it cannot check: no key (`counter` none), or
// its MAC fails at the counter completed (`counter`).
struct Unverified {
  std::optional<std::uint64_t> counter;
};

using FrameReading = std::variant<Broken, Echo, Elsewhere, PlainCommand, PlainRoomStop, PlainRenewal, RoomStop,
                                  JointRenewal, Synchronisation, SealedCommand, Unverified>;

// What a reading depends on besides the bits: this robot's address and keys, its counter
// state, and its memory of frames taken.
struct ReadingContext {
  std::uint8_t address = 0;
  const security::LinkKey* key = nullptr;       // none: takes no sealed frame of its own
  const security::LinkKey* room_key = nullptr;  // none: no stop for every robot is sealed here
  std::uint64_t last_accepted = 0;              // the counter a command's low bits complete from
  // The counter of the sealed velocity taken last, while nothing came after it: what a joint
  // renewal renews (none: nothing to renew).
  std::optional<std::uint64_t> renewable_counter;
  const reliability::EchoMemory* echoes = nullptr;
};

// The payload a synchronisation's MAC holds for (it carries none).
inline constexpr std::uint32_t kSyncPayload = 0;
// What the MAC of `frame` covers, for `counter` as completed and `payload` (a frame in
// synchronisation form carries none).
security::FrameMacInput sealed_mac_input(const reliability::SealedFrame& frame, std::uint64_t counter,
                                         std::uint32_t payload);

// Every reading of an 80-bit frame that a MAC decides, each checked: as many may hold as
// chance allows (a 32-bit MAC one time in 2^32, an 18-bit slot one in 2^18).
struct SealedVerification {
  bool room_stop = false;                        // sync form, MAC holds under the room key
  std::optional<std::uint32_t> command_payload;  // MAC holds under this robot's key, for this payload
  std::uint64_t command_counter = 0;             // the counter it was checked at
  std::optional<std::uint64_t> renewal_counter;  // this robot's renewal slot holds, at this counter
  bool any() const { return room_stop || command_payload || renewal_counter; }
};
// The checks of `frame` (whose CRC holds; `bits` as heard). Allocates nothing: the receive
// path asks it of every candidate decode (HopFramePath).
SealedVerification verify_sealed(const reliability::SealedFrame& frame, const reliability::FrameBits& bits,
                                 const ReadingContext& context);

// The reading an 80-bit frame is given, from what verified.
enum class SealedKind : std::uint8_t { RoomStop, OwnCommand, JointRenewal, Unverified, Elsewhere };
// The rule where readings collide, and why:
//  - the room key's stop before anything under this robot's key: a stop taken for a command
//    would stop nobody else, a command taken for a stop only stops this robot (safe);
//  - a command for this address before a renewal: its MAC is 32 bits, the slot's 18, so one
//    frame in 2^18 of a sender's commands passes a slot by chance, and a Stop taken for a
//    renewal would be neither executed nor answered;
//  - a frame for this address that nothing verifies is this robot's to refuse; any other is
//    another robot's.
constexpr SealedKind sealed_kind(bool room_stop_holds, bool command_holds, bool renewal_holds, bool addressed_here) {
  if (room_stop_holds) return SealedKind::RoomStop;
  if (command_holds && addressed_here) return SealedKind::OwnCommand;
  if (renewal_holds) return SealedKind::JointRenewal;
  return addressed_here ? SealedKind::Unverified : SealedKind::Elsewhere;
}

// The kinds, in the variant's order: what the admission's rules are written over
// (admission_rules.h).
enum class FrameKind : std::uint8_t {
  Broken,
  Echo,
  Elsewhere,
  PlainCommand,
  PlainRoomStop,
  PlainRenewal,
  RoomStop,
  JointRenewal,
  Synchronisation,
  SealedCommand,
  Unverified,
};
static_assert(std::variant_size_v<FrameReading> == static_cast<std::size_t>(FrameKind::Unverified) + 1);
inline FrameKind kind_of(const FrameReading& reading) { return static_cast<FrameKind>(reading.index()); }
// "broken", "echo", "elsewhere", "plain_command", ...: for test names and logs.
std::string_view kind_name(FrameKind kind);

// `heard` read once: `sealed` whether it is an 80-bit frame (three chords).
FrameReading read_frame(const HeardHopFrame& heard, bool sealed, const ReadingContext& context);

}  // namespace dtmf::link::reading
