// What the sender put on the air and heard there, as it happened: the entries of the air's
// fan-out (air_fanout.h), which WatchAir serves (watch_air_rpc.h) and any other watcher
// reads. Each carries when it happened twice: on the microphone's sample clock (audio_ms,
// milliseconds of audio since the sender began to listen, the one clock both of its sides
// share) and on the wall clock, for people.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rows.h"

namespace dtmf::server {

// A frame put on the air (Transmitting, Retransmitting).
struct FramePlayed {
  std::string command_id;
  std::string command;              // the command's description
  std::vector<std::string> robots;  // the robot; a joint renewal's; empty: every robot
  std::string kind;                 // "command", "synchronisation", "renewal", "stop_every_robot"
  std::string profile;
  std::optional<unsigned> sequence;
  std::optional<std::uint64_t> counter;
  bool authenticated = false;
  int frame_index = 0;
  int frame_count = 0;
  int attempt = 0;
  double chord_ms = 0;
  double air_wait_ms = 0;
};

// What the sender took as the answer to a frame's attempt ("ack", "nack"), or "none".
struct FrameAnswered {
  std::string command_id;
  std::string robot;
  int frame_index = 0;
  int attempt = 0;
  std::string answer;
  bool authenticated = false;
  std::optional<double> response_time_ms;
};

// An answer the microphone read, whoever it was for.
struct AnswerHeard {
  std::string robot;  // ours, by the address it names; empty: none of ours, or unnamed
  std::string profile;
  bool ack = false;
  std::optional<unsigned> sequence;
  bool tagged = false;
  std::optional<unsigned> address;
  double level_dbfs = 0;
};

struct AirWaiting {
  std::string command_id;
  std::string robot;
  std::string reason;
  double left_ms = 0;
};

struct AirBusy {
  bool busy = false;
  double level_dbfs = 0;
  double floor_dbfs = 0;
};

struct CommandEnded {
  std::string command_id;
  std::string robot;  // empty: every robot
  std::string command;
  std::string outcome;
  std::string detail;
};

// bins[i]: the loudest level, in dBFS, between low_hz + i * step_hz and low_hz + (i + 1) * step_hz.
struct SpectrumColumn {
  double low_hz = 0;
  double step_hz = 0;
  double window_ms = 0;
  std::vector<float> level_dbfs;
};

struct AirEvent {
  double audio_ms = 0;
  store::WallTime wall{};
  std::variant<FramePlayed, FrameAnswered, AnswerHeard, AirWaiting, AirBusy, CommandEnded, SpectrumColumn> what;
};

// Whether a watcher of `robot` (empty: of every robot) is shown `event`: what names the robot,
// and what concerns the whole room (the air busy, a stop for every robot, an answer naming none
// of ours, the spectrum).
bool concerns(const AirEvent& event, const std::string& robot);

}  // namespace dtmf::server
