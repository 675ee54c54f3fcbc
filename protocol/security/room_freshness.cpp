#include "security/room_freshness.h"

#include <algorithm>

namespace dtmf::security {

Freshness RoomFreshness::check(std::uint64_t counter, std::uint64_t clock_counter) const {
  if (counter_ahead(counter, clock_counter)) return Freshness::Ahead;
  const std::uint64_t window_floor = newest_ > kRoomWindow ? newest_ - kRoomWindow : 0;
  if (counter == 0 || counter <= std::max(floor_, window_floor)) return Freshness::Stale;
  return taken_.contains(counter) ? Freshness::Repeat : Freshness::New;
}

void RoomFreshness::take(std::uint64_t counter) {
  newest_ = std::max(newest_, counter);
  taken_.insert(counter);
  const std::uint64_t window_floor = newest_ > kRoomWindow ? newest_ - kRoomWindow : 0;
  floor_ = std::max(floor_, window_floor);
  taken_.erase(taken_.begin(), taken_.upper_bound(floor_));
  while (taken_.size() > kRoomRemembered) {
    floor_ = *taken_.begin();
    taken_.erase(taken_.begin());
  }
}

std::optional<std::uint64_t> RoomFreshness::reanchor(std::uint64_t clock_counter) {
  if (!counter_ahead(newest_, clock_counter)) return std::nullopt;
  newest_ = clock_counter > kRoomWindow ? clock_counter - kRoomWindow : 0;
  floor_ = newest_;  // the counters taken in the window stay taken: played again, they are repeats
  return newest_;
}

}  // namespace dtmf::security
