#include "security/counter_file.h"

#include "security/owned_file.h"

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

namespace dtmf::security {

namespace {

// 2026-01-01T00:00:00Z.
constexpr std::chrono::seconds kEpoch{1767225600};
// Longer than any file written here ("reserved N\nconfirmed M\n" with 11-digit values).
constexpr std::size_t kLongestState = 4096;

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error(what + " " + path.string() + ": " + std::strerror(errno));
}

using counter_text::Damage;
using counter_text::expect_end;
using counter_text::take_line;

// The file `name` in the directory, or nothing when there is none. Never read through a
// symbolic link, and only a regular file.
std::optional<std::string> read_state(int directory_fd, const std::filesystem::path& path, const std::string& name) {
  // O_NONBLOCK: a FIFO in its place must not hang the program.
  const int fd = ::openat(directory_fd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return std::nullopt;
    if (errno == ELOOP) throw Damage{"it is a symbolic link (a counter file is never read through one)"};
    fail("cannot read the counter state", path);
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd);
    throw Damage{"it is not a regular file"};
  }
  std::string text;
  char buffer[1024];
  while (text.size() <= kLongestState) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      ::close(fd);
      errno = error;
      fail("cannot read the counter state", path);
    }
    if (got == 0) break;
    text.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(fd);
  if (text.size() > kLongestState) throw Damage{"it is longer than any counter state"};
  return text;
}

}  // namespace

std::uint64_t clock_counter_floor(std::chrono::system_clock::time_point now) {
  const auto since = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()) -
                     std::chrono::duration_cast<std::chrono::milliseconds>(kEpoch);
  if (since.count() <= 0) return 1;
  return 1 + static_cast<std::uint64_t>(since.count()) * kCountersPerSecond / 1000;
}

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
  const std::string fix = " (give --state-dir a directory this user may write)";
  std::error_code error;
  if (!std::filesystem::is_directory(directory_, error)) {
    std::filesystem::create_directories(directory_, error);
    if (!error) std::filesystem::permissions(directory_, std::filesystem::perms::owner_all, error);
    if (error) {
      throw std::runtime_error("cannot make the state directory " + directory_.string() + ": " + error.message() + fix);
    }
  }
  // The directory's own path is the operator's (systemd's StateDirectory= with DynamicUser=
  // is a link to /var/lib/private/...), so it is followed; nothing in it ever is.
  directory_fd_ = ::open(directory_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory_fd_ < 0) {
    throw std::runtime_error("cannot open the state directory " + directory_.string() + ": " + std::strerror(errno) +
                             fix);
  }
  struct stat status {};
  std::string refusal;
  if (::fstat(directory_fd_, &status) != 0) {
    refusal = "cannot read the state directory " + directory_.string() + ": " + std::strerror(errno) + fix;
  } else if (status.st_uid != ::geteuid()) {
    refusal = "the state directory " + directory_.string() + " belongs to user " + std::to_string(status.st_uid) +
              ", not to this one (" + std::to_string(::geteuid()) +
              "): that user could change the counters in it. Give --state-dir a directory of this user's "
              "(chown " +
              std::to_string(::geteuid()) + " " + directory_.string() + "; chmod 700 " + directory_.string() + ")";
  } else if ((status.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    refusal = "the state directory " + directory_.string() + " has mode " + octal_mode(status.st_mode) +
              ": its group or others may write in it, and so could put back an old counter (and old recordings "
              "would be taken again). Make it this user's alone: chmod 700 " +
              directory_.string();
  } else if (::faccessat(directory_fd_, ".", W_OK, 0) != 0) {
    refusal = "cannot write in the state directory " + directory_.string() + ": " + std::strerror(errno) + fix;
  }
  if (!refusal.empty()) {
    ::close(directory_fd_);
    throw std::runtime_error(refusal);
  }
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
  next_ = std::max(reserved_, clock_counter_floor(clock_()));
  reserved_ = next_;
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

}  // namespace dtmf::security
