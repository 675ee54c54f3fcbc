// Store library: the rows both programs log, as the database's tables hold them.
//
// Each row carries a client-made uuid, so that the same row can be written again (an
// update, or a replay after an outage) without becoming two. Rows become JSON objects
// whose keys are the column names of db/migrations/001_schema.sql; absent optionals become
// SQL NULL. Times are wall-clock (system_clock): the report matches the two hosts' rows by
// time, so both hosts' clocks must be synchronised (docs/database.md).
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dtmf::store {

using WallClock = std::chrono::system_clock;
using WallTime = WallClock::time_point;

enum class Table { TestRuns, Commands, FrameAttempts, Receptions };
std::string_view table_name(Table table);

// A random (version 4) uuid, "xxxxxxxx-xxxx-4xxx-yxxx-xxxxxxxxxxxx".
std::string new_id();
// "2026-11-22T15:30:00.123456Z"
std::string iso_time(WallTime time);

struct TestRunRow {
  std::string id = new_id();
  std::string label;
  std::string profile;
  WallTime started_at{};
  std::optional<WallTime> ended_at;
  std::string notes;
  std::string host;
};

struct CommandRow {
  std::string id = new_id();
  std::optional<std::string> run_id;
  std::string kind;  // reset, drive_for_duration, ..., word
  nlohmann::json parameters = nlohmann::json::object();
  std::string profile;
  int frame_count = 1;
  WallTime requested_at{};
  std::optional<WallTime> finished_at;
  std::string outcome = "queued";  // queued, transmitting, confirmed, continued, failed, cancelled, sent
  std::string detail;
  std::string host;                  // the sender
  std::optional<std::string> robot;  // the robot it is for, by name; none for every robot
  std::optional<int> robot_address;  // the address its frames carry
  bool every_robot = false;          // a stop for every robot (migration 010)
};

struct FrameAttemptRow {
  std::string id = new_id();
  std::optional<std::string> run_id;
  std::string command_id;
  int position = 0;            // frame within its command, from 0
  int attempt = 1;             // 1 = first transmission
  std::optional<int> word;     // Word16 frames
  std::string frame = "0";     // the frame's bits, CRC included, as a decimal number (up to 128 bits)
  int frame_width = 16;        // bits: 16 (seed), 50 (fast) or 80 (fast, authenticated)
  bool authenticated = false;  // it carried a MAC
  std::vector<double> tones_hz;
  WallTime chord_started_at{};
  std::optional<WallTime> chord_ended_at;
  std::optional<std::string> answer;  // ack, nack, none
  std::optional<WallTime> answered_at;
  // Migration 014: how long it waited for the air before its chord (listen before talk; 0: at
  // once), and why ("sound 14 dB over the room's floor"; none when it did not wait).
  std::optional<double> air_wait_ms;
  std::optional<std::string> air_wait_reason;
};

struct ReceptionRow {
  std::string id = new_id();
  std::string host;
  std::string profile;
  std::optional<WallTime> started_at;
  WallTime heard_at{};
  std::string frame = "0";  // as in FrameAttemptRow
  int frame_width = 16;
  bool crc_ok = false;
  std::optional<std::string> reply;  // ack, nack
  std::optional<int> word;
  std::string event;
  std::string reason;          // why a refused frame was refused: authentication, payload
  bool authenticated = false;  // its MAC held
  std::string command_state;
  std::string command;
  std::optional<double> linear_mps;
  std::optional<double> angular_radps;  // the column angular_rps (rad/s)
  std::optional<int> robot_address;     // the robot's address (dtmf-agent --address); host names it
};

nlohmann::json to_json(const TestRunRow& row);
nlohmann::json to_json(const CommandRow& row);
nlohmann::json to_json(const FrameAttemptRow& row);
nlohmann::json to_json(const ReceptionRow& row);

}  // namespace dtmf::store
