#include "security/counter_clock.h"

namespace dtmf::security {

namespace {
// 2026-01-01T00:00:00Z.
constexpr std::chrono::seconds kEpoch{1767225600};
}  // namespace

std::uint64_t clock_counter_floor(std::chrono::system_clock::time_point now) {
  const auto since = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()) -
                     std::chrono::duration_cast<std::chrono::milliseconds>(kEpoch);
  if (since.count() <= 0) return 1;
  return 1 + static_cast<std::uint64_t>(since.count()) * kCountersPerSecond / 1000;
}

bool ahead_of_clock(std::uint64_t counter, std::chrono::system_clock::time_point now) {
  return counter_ahead(counter, clock_counter_floor(now));
}

double seconds_ahead_of_clock(std::uint64_t counter, std::chrono::system_clock::time_point now) {
  const std::uint64_t floor = clock_counter_floor(now);
  const double counters =
      counter >= floor ? static_cast<double>(counter - floor) : -static_cast<double>(floor - counter);
  return counters / kCountersPerSecond;
}

}  // namespace dtmf::security
