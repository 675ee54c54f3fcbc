// Security layer: counters that name times. Every sender's counter starts no lower than its
// clock allows (kCountersPerSecond since 2026-01-01: counter_file.h), and the room key's never
// falls below it (room_freshness.h). So a counter also says when, at the latest, it could have
// been taken, and one far ahead of a clock was taken by a clock that ran fast, or planted.
//
// Both ends of a freshness window need a bound (docs/security.md, "Counters ahead of the
// clock"): a robot takes no counter more than kClockMarginS ahead of its own clock, and keeps
// none on disk, so one frame from a fast clock cannot make every later frame look old; a
// sender refuses to start from a stored counter that far ahead of its clock.
// Pure logic: the time is given.
#pragma once

#include <chrono>
#include <cstdint>

namespace dtmf::security {

inline constexpr int kCountersPerSecond = 20;
// How far a counter may lie ahead of the clock that checks it: the clock error between two
// machines that is tolerated. NTP keeps them within milliseconds; a robot that booted without
// network (no real-time clock) may lag by minutes. Below the room's hour (kRoomWindow), so a
// stop from a fast clock cannot push a robot's window past a sender whose clock is right.
inline constexpr std::int64_t kClockMarginS = 600;
inline constexpr std::uint64_t kClockMargin = std::uint64_t{kClockMarginS} * kCountersPerSecond;

// The lowest counter the clock allows at `now`: 1 + kCountersPerSecond per second since
// 2026-01-01 (1 before then).
std::uint64_t clock_counter_floor(std::chrono::system_clock::time_point now);
// Whether `counter` lies more than kClockMargin past `clock_counter` (the clock as a counter):
// the one rule every check of a counter's time uses.
constexpr bool counter_ahead(std::uint64_t counter, std::uint64_t clock_counter) {
  return counter > clock_counter + kClockMargin;
}
// Whether `counter` lies more than kClockMargin ahead of what the clock allows at `now`.
bool ahead_of_clock(std::uint64_t counter, std::chrono::system_clock::time_point now);
// How many seconds `counter` lies ahead of the clock at `now` (negative: behind it).
double seconds_ahead_of_clock(std::uint64_t counter, std::chrono::system_clock::time_point now);

}  // namespace dtmf::security
