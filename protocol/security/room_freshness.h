// Security layer: the freshness of frames under the room key, the key every robot and sender
// of a room holds for the one frame every robot obeys: a stop (docs/security.md, "The room
// key").
//
// Any number of senders hold the room key, each with its own counter. Each counts from its
// clock (counter_file.h, CounterPace::Clock: kCountersPerSecond since 2026-01-01), so their
// counters name times, and two senders' stops reach a robot out of order by as much as their
// clocks differ. A robot therefore takes a room counter that is newer than the newest it took,
// or one no more than kRoomWindow older that it has not taken before: IPsec's anti-replay
// window (RFC 4303 §3.4.3), a set of the counters taken in the window instead of a bitmap,
// since room frames are rare. Only the newest is kept on disk: after a restart the window
// starts empty at it, so nothing at or below it is taken again. At most kRoomRemembered
// counters are remembered; forgetting one closes the window at it.
//
// The window has a top too, the robot's own clock: a counter more than kClockMargin ahead of
// it is Ahead, never taken nor kept (the stop still acts: frame_admission.h), so no sender
// whose clock runs fast, and no holder of the room key, can move the window past the stops of
// senders whose clocks are right. A window whose newest already lies that far ahead (kept
// before this bound, or this robot's clock set back) re-anchors: it starts again as if the
// newest had been taken kRoomWindow before the clock's time, so every stop from a clock
// within the hour is new again, and the robot recovers with nothing edited by hand.
// Pure logic: no I/O; the clock's counter is given.
#pragma once

#include <cstdint>
#include <optional>
#include <set>

#include "security/counter_clock.h"
#include "security/freshness.h"

namespace dtmf::security {

// An hour of counters: senders' clocks may differ by up to that.
inline constexpr std::uint64_t kRoomWindow = std::uint64_t{3600} * kCountersPerSecond;
inline constexpr std::size_t kRoomRemembered = 1024;

class RoomFreshness {
 public:
  // `newest_taken`: what the robot's store kept (0: none yet).
  explicit RoomFreshness(std::uint64_t newest_taken) : newest_(newest_taken), floor_(newest_taken) {}
  // New: take it. Repeat: taken before. Stale: older than the window (or than the newest
  // taken before a restart). Ahead: more than kClockMargin past `clock_counter`, the robot's
  // clock as a counter (counter_clock.h).
  Freshness check(std::uint64_t counter, std::uint64_t clock_counter) const;
  // Records `counter` (checked New).
  void take(std::uint64_t counter);
  // Re-anchors the window to `clock_counter` when its newest lies more than kClockMargin
  // ahead of it; returns the newest to keep on disk then (the window's new floor).
  std::optional<std::uint64_t> reanchor(std::uint64_t clock_counter);
  std::uint64_t newest() const { return newest_; }

 private:
  std::uint64_t newest_;
  std::uint64_t floor_;            // counters at or below it are stale, whatever the window says
  std::set<std::uint64_t> taken_;  // above floor_
};

}  // namespace dtmf::security
