#include "security/counter_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "security/counter_text.h"
#include "security/freshness.h"
#include "security/state_directory.h"

namespace dtmf::security {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error(what + " " + path.string() + ": " + std::strerror(errno));
}

using counter_text::Damage;
using counter_text::expect_end;
using counter_text::take_line;

}  // namespace

std::shared_ptr<FileCounterStore> FileCounterStore::open_sender(std::filesystem::path directory, const LinkKey& key,
                                                                Clock clock, CounterPace pace) {
  std::shared_ptr<FileCounterStore> store(
      new FileCounterStore(std::move(directory), key, Role::Sender, std::move(clock)));
  store->pace_ = pace;
  store->start_sender();
  return store;
}

std::shared_ptr<FileCounterStore> FileCounterStore::open_robot(std::filesystem::path directory, const LinkKey& key,
                                                               RobotKey start) {
  std::shared_ptr<FileCounterStore> store(new FileCounterStore(std::move(directory), key, Role::Robot, {}));
  store->start_robot(start);
  return store;
}

FileCounterStore::FileCounterStore(std::filesystem::path directory, const LinkKey& key, Role role, Clock clock)
    : directory_(std::move(directory)), key_id_(key.id_hex()), role_(role), clock_(std::move(clock)) {
  directory_fd_ = open_state_directory(directory_);
}

FileCounterStore::~FileCounterStore() {
  if (role_ == Role::Sender && lock_fd_ >= 0 && confirmed_unwritten_) {
    // The confirmed hint, for a clean restart without a synchronisation frame.
    try {
      write_sender();
    } catch (const std::exception&) {
    }
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
  if (directory_fd_ >= 0) ::close(directory_fd_);
}

void FileCounterStore::take_lock(const std::string& role) {
  const std::string name = role + "-" + key_id_ + ".lock";
  const int fd = ::openat(directory_fd_, name.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) fail("cannot open the lock", directory_ / name);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw std::runtime_error("another process keeps its " + role + " counter in " + directory_.string() + " for key " +
                             key_id_ +
                             ": two would reuse counter values; stop it, or give this one "
                             "its own --state-dir");
  }
  lock_fd_ = fd;
}

// Replaces the file `name` with `text`, durably and atomically, never through a link.
void FileCounterStore::write_file(const std::string& name, const std::string& text) const {
  const std::string temporary = name + ".new";
  // A temporary left by a crash, or anything planted in its place (a link is removed, not followed).
  if (::unlinkat(directory_fd_, temporary.c_str(), 0) != 0 && errno != ENOENT) {
    fail("cannot remove the old temporary", directory_ / temporary);
  }
  const int fd = ::openat(directory_fd_, temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) fail("cannot write the counter state", directory_ / temporary);
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  errno = error;
  if (!ok) fail("cannot write the counter state", directory_ / temporary);
  if (::renameat(directory_fd_, temporary.c_str(), directory_fd_, name.c_str()) != 0) {
    fail("cannot replace the counter state", directory_ / name);
  }
  if (::fsync(directory_fd_) != 0) fail("cannot sync the state directory", directory_);
}

void FileCounterStore::require(Role role, const char* what) const {
  if (role_ != role) {
    throw std::logic_error(std::string(what) + ": this counter store of key " + key_id_ + " is the " +
                           (role_ == Role::Sender ? "sender's" : "robot's"));
  }
}

void FileCounterStore::start_sender() {
  take_lock("sender");
  const std::string name = "sender-" + key_id_;
  const std::filesystem::path path = directory_ / name;
  try {
    if (const auto text = read_state(directory_fd_, path, name)) {
      std::string_view rest = *text;
      reserved_ = take_line(rest, "reserved", 1);
      if (!rest.empty()) last_confirmed_ = take_line(rest, "confirmed", 2);
      expect_end(rest);
    }
  } catch (const Damage& damage) {
    throw std::runtime_error("the counter state " + path.string() + " is damaged: " + damage.what +
                             ". This sender cannot tell which counters it used. Remove the file: its counters then "
                             "start from the clock, above all it used unless it averaged more than " +
                             std::to_string(kCountersPerSecond) +
                             " frames a second (docs/security.md, \"Recovering a lost counter\"); or make a new key "
                             "(dtmfctl keygen) and install it on both sides");
  }
  stored_ = reserved_;
  refuse_future_reservation(path);
  next_ = std::max(reserved_, clock_counter_floor(clock_()));
  reserved_ = next_;
}

// A reservation far ahead of this clock would make every frame a robot's future to refuse
// (counter_clock.h); taken as found, one planted counter would disable the key for good.
void FileCounterStore::refuse_future_reservation(const std::filesystem::path& path) const {
  const auto now = clock_();
  if (!ahead_of_clock(reserved_, now)) return;
  const auto ahead_s = static_cast<long long>(seconds_ahead_of_clock(reserved_, now));
  throw std::runtime_error(
      "the counter state " + path.string() + " holds counter " + std::to_string(reserved_) + ", " +
      std::to_string(ahead_s) + " s (" + std::to_string(ahead_s / 86400) +
      " days) ahead of this machine's clock (its counter now: " + std::to_string(clock_counter_floor(now)) +
      "); robots take no counter more than " + std::to_string(kClockMarginS) +
      " s ahead of their own clocks, so nothing sent from it would be taken. If this machine's clock is behind, set "
      "it (timedatectl; NTP). If the clock is right, a clock that ran fast (or someone) wrote it: remove the file, "
      "and the counters start from the clock; with a robot's own key that took such counters before this check "
      "existed, also make a new key (dtmfctl keygen) and pair both sides again (docs/security.md, \"Counters ahead "
      "of the clock\")");
}

void FileCounterStore::start_robot(RobotKey start) {
  take_lock("robot");
  const std::string name = "robot-" + key_id_;
  const std::filesystem::path path = directory_ / name;
  std::optional<std::uint64_t> accepted;
  try {
    if (const auto text = read_state(directory_fd_, path, name)) {
      std::string_view rest = *text;
      accepted = take_line(rest, "accepted", 1);
      expect_end(rest);
    }
  } catch (const Damage& damage) {
    throw std::runtime_error("the counter state " + path.string() + " is damaged: " + damage.what +
                             ". The robot cannot tell which frames are old. Make a new key (dtmfctl keygen), "
                             "install it on both sides, and start dtmf-agent --new-key");
  }
  if (start == RobotKey::Room && !accepted) {
    write_file(name, "accepted 0\n");
    last_accepted_ = 0;
    return;
  }
  if (start == RobotKey::New) {
    if (accepted) {
      throw std::runtime_error("key " + key_id_ + " has been used here (last accepted " + std::to_string(*accepted) +
                               ", in " + path.string() + "): drop --new-key");
    }
    write_file(name, "accepted 0\n");
    last_accepted_ = 0;
    return;
  }
  if (!accepted) {
    throw std::runtime_error("no counter state for key " + key_id_ + " in " + directory_.string() +
                             ": if this key was just made, start once with --new-key; if the robot lost its "
                             "state, make a new key (dtmfctl keygen), install it on both sides, and start "
                             "dtmf-agent --new-key (with this key it would take old recordings again)");
  }
  last_accepted_ = *accepted;
  stored_ = *accepted;
}

void FileCounterStore::write_sender() {
  std::ostringstream text;
  text << "reserved " << reserved_ << "\n";
  if (last_confirmed_) text << "confirmed " << *last_confirmed_ << "\n";
  write_file("sender-" + key_id_, text.str());
  confirmed_unwritten_ = false;
}

std::uint64_t FileCounterStore::next_counter() { return next_counter_from(0); }

std::uint64_t FileCounterStore::next_counter_from(std::uint64_t at_least) {
  std::lock_guard lock(mutex_);
  require(Role::Sender, "next_counter");
  next_ = std::max(next_, at_least);
  if (pace_ == CounterPace::Clock) next_ = std::max(next_, clock_counter_floor(clock_()));
  if (next_ >= reserved_) {
    if (next_ + kSenderBlock >= kCounterLimit) {
      throw std::runtime_error("the freshness counter of key " + key_id_ +
                               " is used up: make a new key (dtmfctl keygen)");
    }
    reserved_ = next_ + kSenderBlock;
    write_sender();  // on disk before any counter of the block is handed out
  }
  return next_++;
}

std::optional<std::uint64_t> FileCounterStore::last_confirmed() const {
  std::lock_guard lock(mutex_);
  require(Role::Sender, "last_confirmed");
  return last_confirmed_;
}

// Kept in memory and written with the next reservation or at exit: a hint that saves a synchronisation
// frame, never what keeps a counter from being used twice.
void FileCounterStore::confirmed(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  require(Role::Sender, "confirmed");
  last_confirmed_ = std::max(last_confirmed_.value_or(0), counter);
  confirmed_unwritten_ = true;
}

std::uint64_t FileCounterStore::last_accepted() const {
  std::lock_guard lock(mutex_);
  require(Role::Robot, "last_accepted");
  return last_accepted_;
}

void FileCounterStore::accept(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  require(Role::Robot, "accept");
  if (counter <= last_accepted_) return;
  write_file("robot-" + key_id_, "accepted " + std::to_string(counter) + "\n");
  last_accepted_ = counter;
}

void FileCounterStore::reanchor(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  require(Role::Robot, "reanchor");
  write_file("robot-" + key_id_, "accepted " + std::to_string(counter) + "\n");
  last_accepted_ = counter;
}

}  // namespace dtmf::security
