// Test helper: a fresh directory under /tmp, removed with everything in it when it goes.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>

namespace dtmf::test_support {

struct TempDir {
  std::filesystem::path path;
  // `prefix` names the test in /tmp, e.g. "dtmf-key" -> /tmp/dtmf-key-Ab12Cd.
  explicit TempDir(const std::string& prefix) {
    std::string name = "/tmp/" + prefix + "-XXXXXX";
    path = ::mkdtemp(name.data());
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

}  // namespace dtmf::test_support
