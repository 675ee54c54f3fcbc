// Security layer: freshness values — which counter a frame's low bits stand for, whether it
// is newer than the last one the robot accepted, and when the sender must send all of it.
//
// The sender numbers every authenticated frame with a counter that never repeats
// (counter_store.h). A command frame carries only its low `kCounterLowBits` bits; the robot
// completes them to the one counter in [last, last + kCounterWindow) that ends in those bits,
// where `last` is the counter it accepted last (AUTOSAR SecOC's freshness value completion).
// The MAC covers the full counter, so a frame completed to the wrong counter fails it. The
// completed counter equal to `last` is the last frame again (a retransmission after a lost
// ACK, or its replay): answered, not executed. A synchronisation frame carries the whole
// counter; the sender sends one first when the robot may be unable to complete the next
// counter: it has no confirmed frame on record, or its counter ran a window or more past the
// last confirmed one (every counter the robot accepted lies at or after that one).
// Pure logic: no I/O, no clock.
#pragma once

#include <cstdint>
#include <optional>

namespace dtmf::security {

inline constexpr int kCounterLowBits = 9;
inline constexpr std::uint64_t kCounterWindow = std::uint64_t{1} << kCounterLowBits;  // 512
inline constexpr int kCounterBits = 36;  // what a synchronisation frame carries
inline constexpr std::uint64_t kCounterLimit = std::uint64_t{1} << kCounterBits;

// The counter in [last, last + kCounterWindow) whose low bits are `low`.
std::uint64_t complete_counter(std::uint64_t last_accepted, std::uint32_t low);
std::uint32_t counter_low_bits(std::uint64_t counter);

// Ahead: more than kClockMargin ahead of the checking robot's clock (counter_clock.h): never
// taken nor kept, whatever else holds.
enum class Freshness { New, Repeat, Stale, Ahead };
// `counter` against the last accepted one (0: none yet; counters start at 1) and the robot's
// clock as a counter (counter_clock.h): Ahead before anything else.
Freshness freshness_of(std::uint64_t last_accepted, std::uint64_t counter, std::uint64_t clock_counter);

// Whether the robot can complete `counter` from its low bits, knowing only that it accepted
// `last_confirmed` (or nothing on record).
bool completable(std::optional<std::uint64_t> last_confirmed, std::uint64_t counter);

}  // namespace dtmf::security
