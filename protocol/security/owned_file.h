// Security layer: what every reader of a secret or a state file shares — a descriptor
// closed on every way out, and a file's mode as people write it ("0644"), for the errors that
// refuse a file others may read or write (link_key.cpp, counter_file.cpp, the server's
// secret_file.cpp). Header-only.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <string>

namespace dtmf::security {

// The permission bits of `mode` in octal, four digits: "0600".
inline std::string octal_mode(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// Closes a file descriptor on every way out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace dtmf::security
