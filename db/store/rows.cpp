#include "rows.h"

#include <cstdio>
#include <ctime>
#include <mutex>
#include <random>

namespace dtmf::store {

std::string_view table_name(Table table) {
  switch (table) {
    case Table::TestRuns:
      return "test_runs";
    case Table::Commands:
      return "commands";
    case Table::FrameAttempts:
      return "frame_attempts";
    case Table::Receptions:
      return "receptions";
  }
  return "";
}

std::string new_id() {
  static std::mutex mutex;
  static std::mt19937_64 rng{std::random_device{}()};
  std::uint64_t hi, lo;
  {
    std::lock_guard lock(mutex);
    hi = rng();
    lo = rng();
  }
  hi = (hi & 0xFFFFFFFFFFFF0FFFull) | 0x0000000000004000ull;  // version 4
  lo = (lo & 0x3FFFFFFFFFFFFFFFull) | 0x8000000000000000ull;  // RFC 4122 variant
  char text[37];
  std::snprintf(text, sizeof text, "%08x-%04x-%04x-%04x-%012llx", static_cast<unsigned>(hi >> 32),
                static_cast<unsigned>((hi >> 16) & 0xFFFF), static_cast<unsigned>(hi & 0xFFFF),
                static_cast<unsigned>(lo >> 48), static_cast<unsigned long long>(lo & 0xFFFFFFFFFFFFull));
  return text;
}

std::string iso_time(WallTime time) {
  const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(time.time_since_epoch()).count();
  const std::time_t seconds = static_cast<std::time_t>(micros / 1000000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%06lldZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<long long>(micros % 1000000));
  return text;
}

namespace {

template <class T>
nlohmann::json optional_json(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json optional_time(const std::optional<WallTime>& time) {
  return time ? nlohmann::json(iso_time(*time)) : nlohmann::json(nullptr);
}

nlohmann::json text_or_null(const std::string& text) {
  return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
}

}  // namespace

nlohmann::json to_json(const TestRunRow& r) {
  return {{"id", r.id},
          {"label", r.label},
          {"profile", r.profile},
          {"started_at", iso_time(r.started_at)},
          {"ended_at", optional_time(r.ended_at)},
          {"notes", text_or_null(r.notes)},
          {"host", text_or_null(r.host)}};
}

nlohmann::json to_json(const CommandRow& r) {
  nlohmann::json row = {{"id", r.id},
                        {"run_id", optional_json(r.run_id)},
                        {"kind", r.kind},
                        {"parameters", r.parameters},
                        {"profile", r.profile},
                        {"frame_count", r.frame_count},
                        {"requested_at", iso_time(r.requested_at)},
                        {"finished_at", optional_time(r.finished_at)},
                        {"outcome", r.outcome},
                        {"detail", text_or_null(r.detail)},
                        {"host", text_or_null(r.host)}};
  // Migration 010's columns.
  row["robot"] = optional_json(r.robot);
  row["robot_address"] = optional_json(r.robot_address);
  row["every_robot"] = r.every_robot;
  return row;
}

nlohmann::json to_json(const FrameAttemptRow& r) {
  nlohmann::json row = {{"id", r.id},
                        {"run_id", optional_json(r.run_id)},
                        {"command_id", r.command_id},
                        {"position", r.position},
                        {"attempt", r.attempt},
                        {"word", optional_json(r.word)},
                        {"frame", r.frame},
                        {"frame_width", r.frame_width},
                        {"authenticated", r.authenticated},
                        {"tones_hz", r.tones_hz},
                        {"chord_started_at", iso_time(r.chord_started_at)},
                        {"chord_ended_at", optional_time(r.chord_ended_at)},
                        {"answer", optional_json(r.answer)},
                        {"answered_at", optional_time(r.answered_at)}};
  // Migration 014's columns: a database before it ignores them (store_rows writes the columns it has).
  row["air_wait_ms"] = optional_json(r.air_wait_ms);
  row["air_wait_reason"] = optional_json(r.air_wait_reason);
  return row;
}

nlohmann::json to_json(const ReceptionRow& r) {
  nlohmann::json row = {{"id", r.id},
                        {"host", text_or_null(r.host)},
                        {"profile", r.profile},
                        {"started_at", optional_time(r.started_at)},
                        {"heard_at", iso_time(r.heard_at)},
                        {"frame", r.frame},
                        {"frame_width", r.frame_width},
                        {"crc_ok", r.crc_ok},
                        {"reply", optional_json(r.reply)},
                        {"word", optional_json(r.word)},
                        {"event", text_or_null(r.event)},
                        {"reason", text_or_null(r.reason)},
                        {"authenticated", r.authenticated},
                        {"command_state", text_or_null(r.command_state)},
                        {"command", text_or_null(r.command)},
                        {"linear_mps", optional_json(r.linear_mps)},
                        {"angular_rps", optional_json(r.angular_radps)}};
  row["robot_address"] = optional_json(r.robot_address);  // migration 010
  return row;
}

}  // namespace dtmf::store
