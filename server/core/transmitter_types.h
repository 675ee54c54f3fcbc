// What the transmitter (transmitter.h) is given and tells: the robots it drives, its options,
// and how it shared the air. Its refusals of commands are values (refusal.h).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command/robot_model.h"
#include "link/link.h"
#include "rows.h"

namespace dtmf::server {

// What sendable_profile() throws for a command under a profile without a MAC, from a sender
// with a key that was not told to allow it (submit() returns it as Refusal::Unauthenticated).
class UnauthenticatedRefused : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// One robot the transmitter drives: its name, its TurtleBot3 model, and its links (one per
// profile, link::make_links with the robot's address and key).
struct RobotLinks {
  std::string name = "robot";
  command::RobotModel model = command::burger();
  std::vector<std::unique_ptr<link::Link>> links;
};
// A robot's place among the transmitter's robots; 0 is the first (the only one by default).
using RobotIndex = std::size_t;

// What a sender knows of a robot (ListRobots).
struct RobotStatus {
  std::string name;
  std::uint8_t address = 0;
  std::string key_id;  // hex; empty without a key
  std::string model;
  std::optional<store::WallTime> last_answered;  // its last answer heard, if any
};

struct TransmitterOptions {
  std::size_t max_queue = 32;
  // Run the loudspeaker thread at real-time priority (physical/realtime_priority.h): the program
  // does, in-process tests need not. The microphone's reader decodes, so it never is: a device
  // is drained by a thread of its own (physical/capture_thread.h).
  bool realtime_audio = false;
  // With a key: commands may name a profile whose frames carry no MAC (the seed's), and be
  // confirmed by an untagged ACK (dtmf-server --allow-unauthenticated-commands). Stop still
  // goes authenticated.
  bool allow_unauthenticated = false;
  // Listen before talk (reliability/air_access.h): defer to other senders' frames and answers
  // heard on the microphone. Off only to measure what it saves (tests and benchmarks).
  bool listen_before_talk = true;
  // The seed of its random backoff; none: from the clock, so that two senders differ.
  std::optional<std::uint64_t> backoff_seed = std::nullopt;
};

// How this sender shared the air (listen before talk), for tests and logs.
struct AirShare {
  std::uint64_t deferred = 0;        // frames that waited for another's sound
  std::uint64_t answered_waits = 0;  // ... only the short quiet, after an answer the ear read
  std::uint64_t yields = 0;          // pauses made to let the others in
  std::uint64_t listens = 0;         // pauses made, alone, to hear whether others wait
  std::uint64_t busy_blocks = 0;     // microphone blocks heard busy with another's sound
  std::uint64_t others_answers = 0;  // answers the ear read that were another's
  std::uint64_t masked_answers = 0;  // ... read under our own exchange: another's went on under it
};

}  // namespace dtmf::server
