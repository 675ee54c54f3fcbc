// Test helper: a whole file as text ("" when it cannot be read), for logs and state files.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dtmf::test_support {

inline std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace dtmf::test_support
