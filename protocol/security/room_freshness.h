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
// Pure logic: no I/O, no clock.
#pragma once

#include <cstdint>
#include <set>

#include "security/counter_file.h"
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
  // taken before a restart).
  Freshness check(std::uint64_t counter) const;
  // Records `counter` (checked New).
  void take(std::uint64_t counter);
  std::uint64_t newest() const { return newest_; }

 private:
  std::uint64_t newest_;
  std::uint64_t floor_;            // counters at or below it are stale, whatever the window says
  std::set<std::uint64_t> taken_;  // above floor_
};

}  // namespace dtmf::security
