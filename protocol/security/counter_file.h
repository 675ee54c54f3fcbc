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
// robot's accepted counter is on disk before the frame acts or is answered.
//
// Failing closed. A file is read only in the exact form written here; anything else (empty,
// cut short, an unknown line, a value that is no number, anything after the last line) is
// damaged, and a damaged file stops the program with what to do. A robot with no file for
// its key refuses to start: it could not tell an old recording from a new frame. A key just
// made is declared so once (RobotKey::New, dtmf-agent --new-key), which writes "accepted 0"
// and is refused when the key already has state. A sender with no file is safe (it starts
// above the clock's floor).
//
// The directory is trusted only when it is this user's and no one else may write in it
// (made with mode 0700 when missing). It is opened once; every file in it is opened, made,
// renamed and removed relative to it, and never through a symbolic link: a link planted as
// a counter file or its temporary is refused or removed, never written through.
//
// One process per role and key: a lock (flock), taken when the store opens, refuses a second
// one. Files are made with mode 0600.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "security/counter_clock.h"
#include "security/counter_store.h"
#include "security/link_key.h"

namespace dtmf::security {

inline constexpr std::uint64_t kSenderBlock = 32;

// What a robot's store expects to find for its key.
enum class RobotKey {
  Paired,  // the key's state is on disk: missing, the robot cannot tell which frames are old
  New,     // the key was just made (dtmf-agent --new-key): "accepted 0" is written, and state
           // already there for it is refused
  Room,    // the room key (room_freshness.h): its frames only stop robots, so with no state
           // "accepted 0" is written and any counter is new; a replayed stop could only stop
           // a robot that missed it, which jamming the air does as well (docs/security.md)
};

// How a sender's counters advance.
enum class CounterPace {
  Frames,  // one per frame, from where the last run stopped (or the clock's floor, if higher)
  Clock,   // never below the clock's floor at the time a counter is taken: the room key's,
           // whose counters, from several senders, must name times (room_freshness.h)
};

class FileCounterStore final : public CounterStore {
 public:
  using Clock = std::function<std::chrono::system_clock::time_point()>;

  // The sender's counters (next_counter, last_confirmed, confirmed): the lock is taken and
  // the file read before this returns; no file means counters start from the clock.
  static std::shared_ptr<FileCounterStore> open_sender(std::filesystem::path directory, const LinkKey& key,
                                                       Clock clock = std::chrono::system_clock::now,
                                                       CounterPace pace = CounterPace::Frames);
  // The robot's accepted counter (last_accepted, accept): the lock is taken and the file read
  // (or, for a new key, written) before this returns.
  static std::shared_ptr<FileCounterStore> open_robot(std::filesystem::path directory, const LinkKey& key,
                                                      RobotKey start = RobotKey::Paired);
  // Both throw std::runtime_error naming the directory or file, what is wrong and what to do.

  ~FileCounterStore() override;
  FileCounterStore(const FileCounterStore&) = delete;
  FileCounterStore& operator=(const FileCounterStore&) = delete;

  // Each role's own; the other role's throw std::logic_error.
  std::uint64_t next_counter() override;
  std::uint64_t next_counter_from(std::uint64_t at_least) override;
  std::optional<std::uint64_t> last_confirmed() const override;
  void confirmed(std::uint64_t counter) override;
  std::uint64_t last_accepted() const override;
  void accept(std::uint64_t counter) override;

  const std::filesystem::path& directory() const { return directory_; }
  // The counter found on disk at start (the sender's reservation, the robot's last accepted):
  // programs warn when it lies ahead of their clock (counter_clock.h).
  std::optional<std::uint64_t> stored_counter() const { return stored_; }
  // The room key's: replaces the newest room counter kept with `counter`, even a lower one,
  // when the room's window re-anchors to the clock (room_freshness.h).
  void reanchor(std::uint64_t counter) override;

 private:
  enum class Role { Sender, Robot };
  FileCounterStore(std::filesystem::path directory, const LinkKey& key, Role role, Clock clock);
  void start_sender();
  void start_robot(RobotKey start);
  void refuse_future_reservation(const std::filesystem::path& path) const;
  void take_lock(const std::string& role);
  void write_sender();
  void write_file(const std::string& name, const std::string& text) const;
  void require(Role role, const char* what) const;

  std::filesystem::path directory_;
  std::string key_id_;
  Role role_;
  Clock clock_;
  CounterPace pace_ = CounterPace::Frames;
  int directory_fd_ = -1, lock_fd_ = -1;
  mutable std::mutex mutex_;
  std::uint64_t next_ = 0, reserved_ = 0, last_accepted_ = 0;
  std::optional<std::uint64_t> last_confirmed_;
  std::optional<std::uint64_t> stored_;
  bool confirmed_unwritten_ = false;
};

}  // namespace dtmf::security
