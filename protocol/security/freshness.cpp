#include "security/freshness.h"

#include "security/counter_clock.h"

namespace dtmf::security {

std::uint64_t complete_counter(std::uint64_t last_accepted, std::uint32_t low) {
  const std::uint64_t mask = kCounterWindow - 1;
  return last_accepted + ((std::uint64_t{low} - last_accepted) & mask);
}

std::uint32_t counter_low_bits(std::uint64_t counter) {
  return static_cast<std::uint32_t>(counter & (kCounterWindow - 1));
}

Freshness freshness_of(std::uint64_t last_accepted, std::uint64_t counter, std::uint64_t clock_counter) {
  if (counter_ahead(counter, clock_counter)) return Freshness::Ahead;
  if (counter == 0 || counter < last_accepted) return Freshness::Stale;
  return counter == last_accepted ? Freshness::Repeat : Freshness::New;
}

bool completable(std::optional<std::uint64_t> last_confirmed, std::uint64_t counter) {
  // The robot's last lies in [last_confirmed, counter): the window must reach from its start.
  return last_confirmed && counter > *last_confirmed && counter - *last_confirmed < kCounterWindow;
}

}  // namespace dtmf::security
