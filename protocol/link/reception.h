// What the robot made of a frame it heard (Reception), and what the sender heard back
// (Answer), whatever the profile's format. Links produce them (link.h); the agent answers,
// logs and executes receptions, the transmitter matches answers to the frame on air.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command/command.h"
#include "reliability/frame_bits.h"
#include "reliability/tag_chord.h"

namespace dtmf::link {

// What a frame did at the robot.
enum class ReceptionEvent {
  Broken,        // failed the check (CRC): answered NACK
  Reset,         // seed words: the RESET word
  ModeSelected,  // seed words: a mode word
  Command,       // a command to execute now (completed by this word, or carried by this frame)
  Ignored,       // seed words: a word the state machine ignored; fast: a renewal of a velocity this robot
                 // does not hold (never answered)
  Repeat,        // the frame executed last, again (a retransmission after a lost ACK): answered, not executed
  Synchronised,  // a counter synchronisation (authenticated frames): answered, no command
  Refused,       // intact, but not executed: answered NACK (see RefusalReason)
  Renewed,       // a joint renewal (reliability/renewal_frame.h, plain_renewal.h): the velocity last taken, its lease
                 // counted again from this frame's start; never answered
};
enum class RefusalReason {
  None,
  Authentication,  // no MAC where the robot has a key, a MAC that fails, a counter not newer, no key to check
  Payload,         // a payload no sender makes (a kind this robot does not know)
};
// "broken", "reset", "mode_selected", "command", "ignored", "repeat", "sync", "refused", "renewal": the
// receptions table's `event` ("" for broken, as the table has always held).
std::string_view event_name(ReceptionEvent event);
// "", "authentication", "payload": the receptions table's `reason`.
std::string_view reason_name(RefusalReason reason);

struct Reception {
  double start_ms = 0;          // when the frame began (fast: where its tones rose, a few ms; seed: a hop)
  double heard_ms = 0;          // when the verdict was reached: the robot's decision time
  reliability::FrameBits bits;  // the frame as accepted, or as first read when broken
  int bit_count = 0;
  int check_bit_count = 0;  // the low bits that are the check
  bool intact = false;      // passed the check (CRC)
  ReceptionEvent event = ReceptionEvent::Broken;
  RefusalReason refusal = RefusalReason::None;
  bool authenticated = false;            // its MAC held under this robot's key
  std::optional<std::uint8_t> sequence;  // numbered unauthenticated frames
  std::optional<std::uint64_t> counter;  // authenticated frames: the counter completed
  // Authenticated frames: the payload their MAC holds for. A frame in synchronisation form
  // carries none: a synchronisation's is 0, a Stop's is STOP (a Stop carries its whole counter).
  std::uint32_t mac_payload = 0;
  // Where a format's payload is one number and its commands span several frames (word
  // frames: the 12-bit word and the word state machine), the intact frame's payload and the
  // receiver's command state after it (empty where the frame was not given to it: refused).
  // Nothing in formats whose frames carry whole commands: `command` says it all.
  std::optional<std::uint32_t> payload_word;
  std::string command_state;
  std::optional<command::Command> command;  // the command to execute now
  std::string detail;                       // for people: what it did, or why it was refused
  std::vector<double> tones_hz;             // the tones that carry `bits`, in order

  // Whether the robot answers at all. In a room of robots only the robot a frame is for may
  // answer it, so a robot keeps quiet about a frame it cannot check (sealed under another
  // key, or sealed where it has no key, or plain where it takes only sealed ones) and about a
  // broken one whose address reads as another robot's: logged and counted, never executed.
  bool answered = true;

  // Answered with ACK: intact and not refused.
  bool acknowledged() const { return intact && event != ReceptionEvent::Refused; }
};

// An ACK or a NACK the sender heard.
struct Answer {
  bool ack = false;
  std::optional<std::uint8_t> sequence;  // named by the ACK, in formats that name frames
  // The ACK to an authenticated frame: its tag chord's bands as heard, which the link checks
  // against the tag the frame on air waits for (Link::answers).
  std::optional<reliability::TagChordReading> tag_reading;
  double heard_ms = 0;
  int lane = 0;              // where an untagged answer sounded: an ACK answers only a frame whose answer_lane it is
  std::uint8_t address = 0;  // the robot that answered, where the answer names it (fast, untagged)
};

// The tones a tagged ACK's bands read as (-1: unheard), for people and tools (dtmfctl
// decode); a sender checks the tag it waits for instead (Link::answers).
inline std::optional<std::array<int, reliability::kTagChordTones>> spelled_tag(const Answer& answer) {
  if (!answer.tag_reading) return std::nullopt;
  return reliability::tag_chord_plain(*answer.tag_reading);
}

}  // namespace dtmf::link
