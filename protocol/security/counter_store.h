// Security layer: where each side keeps its freshness counter (freshness.h).
//
// The sender takes a new counter for every authenticated frame it plans and learns which ones
// the robot confirmed; the robot remembers the last counter it accepted. A counter value must
// never serve two different frames, and the robot must never accept one it accepted before,
// whatever happens to the process (kill -9) or the machine (power loss): FileCounterStore
// (counter_file.h) keeps both on disk; MemoryCounterStore keeps them for one process's life
// (tests, offline tools that are told where to start).
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>

namespace dtmf::security {

class CounterStore {
 public:
  virtual ~CounterStore() = default;

  // --- the sender ---
  // A counter never handed out before by this store (and, for a file, by any process that
  // used it). Throws std::runtime_error when the counter space is used up (rotate the key).
  virtual std::uint64_t next_counter() = 0;
  // The same, and at least `at_least`: the counters below it that were never handed out
  // never will be (a joint renewal gives several robots' links one counter).
  virtual std::uint64_t next_counter_from(std::uint64_t at_least) = 0;
  virtual std::optional<std::uint64_t> last_confirmed() const = 0;
  // The robot confirmed the frame with `counter` (an ACK whose tag held).
  virtual void confirmed(std::uint64_t counter) = 0;

  // --- the robot ---
  // The last counter accepted; 0 before any.
  virtual std::uint64_t last_accepted() const = 0;
  // Records `counter` as accepted; it is kept before this returns (so before the frame acts).
  virtual void accept(std::uint64_t counter) = 0;
  // The room key's alone (room_freshness.h): replaces the counter kept with `counter`, even a
  // lower one, when the room's window re-anchors to the clock. Never a robot's own key's: a
  // lower counter would let its old recordings in again.
  virtual void reanchor(std::uint64_t counter) = 0;
};

class MemoryCounterStore final : public CounterStore {
 public:
  explicit MemoryCounterStore(std::uint64_t first_counter = 1, std::uint64_t last_accepted = 0)
      : next_(first_counter), last_accepted_(last_accepted) {}
  std::uint64_t next_counter() override;
  std::uint64_t next_counter_from(std::uint64_t at_least) override;
  std::optional<std::uint64_t> last_confirmed() const override;
  void confirmed(std::uint64_t counter) override;
  std::uint64_t last_accepted() const override;
  void accept(std::uint64_t counter) override;
  void reanchor(std::uint64_t counter) override;

 private:
  mutable std::mutex mutex_;
  std::uint64_t next_;
  std::optional<std::uint64_t> last_confirmed_;
  std::uint64_t last_accepted_;
};

}  // namespace dtmf::security
