// Test helper: wait for what a test means, not for a time that usually suffices.
//
//   ASSERT_TRUE(wait_until([&] { return robot_stopped(); }, 5s)) << "the robot did not stop";
//
// A sleep is right only where the time is the behaviour under test: "nothing moves for 1 s
// after the Stop", a lease that lapses, a client that stays silent, a real-time stream's
// pace. Say so next to it.
#pragma once

#include <chrono>
#include <thread>

namespace dtmf::test_support {

// Polls `predicate` every `poll` until it holds or `deadline` has passed; whether it held.
// The predicate is tried once more at the deadline, so a slow last poll does not lose it.
template <class Predicate>
bool wait_until(Predicate predicate, std::chrono::milliseconds deadline,
                std::chrono::milliseconds poll = std::chrono::milliseconds(10)) {
  const auto until = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < until) {
    if (predicate()) return true;
    std::this_thread::sleep_for(poll);
  }
  return static_cast<bool>(predicate());
}

}  // namespace dtmf::test_support
