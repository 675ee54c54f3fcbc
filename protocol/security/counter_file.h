// Security layer: the freshness counters on disk, in a state directory (`--state-dir`).
//
//   DIR/sender-<key id>   "reserved N" and "confirmed M": counters below N may have been used
//   DIR/robot-<key id>    "accepted N": the last counter the robot accepted
//
// Each file is replaced whole: a temporary file is written and fsync'd, renamed over it, and
// the directory fsync'd, so after a crash or a power loss it holds the old value or the new
// one, never a torn mix. The sender hands out counters from a block reserved ahead: "reserved
// N + block" is on disk before N is handed out, so a killed sender resumes at its reservation,
// skipping at most a block and never repeating a value. It also starts no lower than the
// clock (kCountersPerSecond since 2026-01-01), so a new machine given the same key starts
// above what an old one used unless that one averaged more frames a second than that. The
// robot's accepted counter is on disk before the frame acts or is answered. One process per
// role and key: a lock (flock) refuses a second one. Files are made with mode 0600.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>

#include "security/counter_store.h"
#include "security/link_key.h"

namespace dtmf::security {

inline constexpr int kCountersPerSecond = 20;
inline constexpr std::uint64_t kSenderBlock = 32;

// The lowest counter the clock allows at `now`.
std::uint64_t clock_counter_floor(std::chrono::system_clock::time_point now);

class FileCounterStore final : public CounterStore {
 public:
  using Clock = std::function<std::chrono::system_clock::time_point()>;
  // Creates `directory` (mode 0700) when it is missing. Files are opened, read and locked on
  // first use of a role. Throws std::runtime_error naming the directory and what to do.
  FileCounterStore(std::filesystem::path directory, const LinkKey& key, Clock clock = std::chrono::system_clock::now);
  ~FileCounterStore() override;

  std::uint64_t next_counter() override;
  std::optional<std::uint64_t> last_confirmed() const override;
  void confirmed(std::uint64_t counter) override;
  std::uint64_t last_accepted() const override;
  void accept(std::uint64_t counter) override;

  const std::filesystem::path& directory() const { return directory_; }

 private:
  void open_sender() const;
  void open_robot() const;
  int lock(const std::string& role) const;
  void write_sender() const;

  std::filesystem::path directory_;
  std::string key_id_;
  Clock clock_;
  mutable std::mutex mutex_;
  mutable int sender_lock_ = -1, robot_lock_ = -1;
  mutable std::uint64_t next_ = 0, reserved_ = 0, last_accepted_ = 0;
  mutable std::optional<std::uint64_t> last_confirmed_;
  mutable bool confirmed_unwritten_ = false;
};

}  // namespace dtmf::security
