#include "security/counter_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "security/freshness.h"

namespace dtmf::security {

namespace {

// 2026-01-01T00:00:00Z.
constexpr std::chrono::seconds kEpoch{1767225600};

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error(what + " " + path.string() + ": " + std::strerror(errno));
}

void fsync_directory(const std::filesystem::path& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) fail("cannot open the state directory", directory);
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) fail("cannot sync the state directory", directory);
}

// Replaces `path` with `text`, durably and atomically.
void replace_file(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path temporary = path.string() + ".new";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) fail("cannot write the counter state", temporary);
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  errno = error;
  if (!ok) fail("cannot write the counter state", temporary);
  if (::rename(temporary.c_str(), path.c_str()) != 0) fail("cannot replace the counter state", path);
  fsync_directory(path.parent_path());
}

// "name value" lines; a missing file reads as empty.
std::optional<std::uint64_t> read_field(const std::filesystem::path& path, const std::string& name) {
  std::ifstream in(path);
  if (!in) {
    if (errno == ENOENT || !std::filesystem::exists(path)) return std::nullopt;
    fail("cannot read the counter state", path);
  }
  std::string field;
  std::uint64_t value = 0;
  while (in >> field >> value) {
    if (field == name) return value;
  }
  if (!in.eof())
    throw std::runtime_error("the counter state " + path.string() + " is damaged: it must hold lines 'name number'");
  return std::nullopt;
}

}  // namespace

std::uint64_t clock_counter_floor(std::chrono::system_clock::time_point now) {
  const auto since = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()) -
                     std::chrono::duration_cast<std::chrono::milliseconds>(kEpoch);
  if (since.count() <= 0) return 1;
  return 1 + static_cast<std::uint64_t>(since.count()) * kCountersPerSecond / 1000;
}

FileCounterStore::FileCounterStore(std::filesystem::path directory, const LinkKey& key, Clock clock)
    : directory_(std::move(directory)), key_id_(key.id_hex()), clock_(std::move(clock)) {
  std::error_code error;
  if (!std::filesystem::is_directory(directory_, error)) {
    std::filesystem::create_directories(directory_, error);
    if (!error) std::filesystem::permissions(directory_, std::filesystem::perms::owner_all, error);
    if (error) {
      throw std::runtime_error("cannot make the state directory " + directory_.string() + ": " + error.message() +
                               " (give --state-dir a directory this user may write)");
    }
  }
  if (::access(directory_.c_str(), W_OK) != 0) {
    throw std::runtime_error("cannot write in the state directory " + directory_.string() + ": " +
                             std::strerror(errno) + " (give --state-dir a directory this user may write)");
  }
}

FileCounterStore::~FileCounterStore() {
  if (sender_lock_ >= 0) {
    // The confirmed hint, for a clean restart without a synchronisation frame.
    try {
      if (confirmed_unwritten_) write_sender();
    } catch (const std::exception&) {
    }
    ::close(sender_lock_);
  }
  if (robot_lock_ >= 0) ::close(robot_lock_);
}

int FileCounterStore::lock(const std::string& role) const {
  const std::filesystem::path path = directory_ / (role + "-" + key_id_ + ".lock");
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) fail("cannot open the lock", path);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw std::runtime_error("another process keeps its " + role + " counter in " + directory_.string() + " for key " +
                             key_id_ +
                             ": two would reuse counter values; stop it, or give this one "
                             "its own --state-dir");
  }
  return fd;
}

void FileCounterStore::open_sender() const {
  if (sender_lock_ >= 0) return;
  sender_lock_ = lock("sender");
  const std::filesystem::path path = directory_ / ("sender-" + key_id_);
  reserved_ = read_field(path, "reserved").value_or(0);
  last_confirmed_ = read_field(path, "confirmed");
  next_ = std::max(reserved_, clock_counter_floor(clock_()));
  reserved_ = next_;
}

void FileCounterStore::write_sender() const {
  std::ostringstream text;
  text << "reserved " << reserved_ << "\n";
  if (last_confirmed_) text << "confirmed " << *last_confirmed_ << "\n";
  replace_file(directory_ / ("sender-" + key_id_), text.str());
  confirmed_unwritten_ = false;
}

std::uint64_t FileCounterStore::next_counter() {
  std::lock_guard lock(mutex_);
  open_sender();
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
  open_sender();
  return last_confirmed_;
}

// Kept in memory and written with the next reservation or at exit: a hint that saves a synchronisation
// frame, never what keeps a counter from being used twice.
void FileCounterStore::confirmed(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  open_sender();
  last_confirmed_ = std::max(last_confirmed_.value_or(0), counter);
  confirmed_unwritten_ = true;
}

void FileCounterStore::open_robot() const {
  if (robot_lock_ >= 0) return;
  robot_lock_ = lock("robot");
  last_accepted_ = read_field(directory_ / ("robot-" + key_id_), "accepted").value_or(0);
}

std::uint64_t FileCounterStore::last_accepted() const {
  std::lock_guard lock(mutex_);
  open_robot();
  return last_accepted_;
}

void FileCounterStore::accept(std::uint64_t counter) {
  std::lock_guard lock(mutex_);
  open_robot();
  if (counter <= last_accepted_) return;
  replace_file(directory_ / ("robot-" + key_id_), "accepted " + std::to_string(counter) + "\n");
  last_accepted_ = counter;
}

}  // namespace dtmf::security
