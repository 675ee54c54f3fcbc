#include "security/state_directory.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "security/counter_text.h"
#include "security/owned_file.h"

namespace dtmf::security {

namespace {

// Longer than any file written here ("reserved N\nconfirmed M\n" with 11-digit values).
constexpr std::size_t kLongestState = 4096;

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error(what + " " + path.string() + ": " + std::strerror(errno));
}

using counter_text::Damage;

}  // namespace

int open_state_directory(const std::filesystem::path& directory) {
  const std::string fix = " (give --state-dir a directory this user may write)";
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    std::filesystem::create_directories(directory, error);
    if (!error) std::filesystem::permissions(directory, std::filesystem::perms::owner_all, error);
    if (error) {
      throw std::runtime_error("cannot make the state directory " + directory.string() + ": " + error.message() + fix);
    }
  }
  // The directory's own path is the operator's (systemd's StateDirectory= with DynamicUser=
  // is a link to /var/lib/private/...), so it is followed; nothing in it ever is.
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    throw std::runtime_error("cannot open the state directory " + directory.string() + ": " + std::strerror(errno) +
                             fix);
  }
  struct stat status {};
  std::string refusal;
  if (::fstat(fd, &status) != 0) {
    refusal = "cannot read the state directory " + directory.string() + ": " + std::strerror(errno) + fix;
  } else if (status.st_uid != ::geteuid()) {
    refusal = "the state directory " + directory.string() + " belongs to user " + std::to_string(status.st_uid) +
              ", not to this one (" + std::to_string(::geteuid()) +
              "): that user could change the counters in it. Give --state-dir a directory of this user's "
              "(chown " +
              std::to_string(::geteuid()) + " " + directory.string() + "; chmod 700 " + directory.string() + ")";
  } else if ((status.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    refusal = "the state directory " + directory.string() + " has mode " + octal_mode(status.st_mode) +
              ": its group or others may write in it, and so could put back an old counter (and old recordings "
              "would be taken again). Make it this user's alone: chmod 700 " +
              directory.string();
  } else if (::faccessat(fd, ".", W_OK, 0) != 0) {
    refusal = "cannot write in the state directory " + directory.string() + ": " + std::strerror(errno) + fix;
  }
  if (!refusal.empty()) {
    ::close(fd);
    throw std::runtime_error(refusal);
  }
  return fd;
}

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

}  // namespace dtmf::security
