// Test helper: run a program as a user would and capture what it says.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace dtmf::test_support {

struct CommandResult {
  int exit_code;
  std::string out;  // stdout, and stderr too unless the command redirects it
};

inline CommandResult run_command(const std::string& command, bool with_stderr = true) {
  FILE* pipe = popen(("(" + command + ")" + (with_stderr ? " 2>&1" : " 2>/dev/null")).c_str(), "r");
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// Every line of `out` that parses as a JSON object.
inline std::vector<nlohmann::json> json_lines(const std::string& out) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.front() != '{') continue;
    lines.push_back(nlohmann::json::parse(line));
  }
  return lines;
}

// Every line of `out`, each of which must be a JSON object (what a JSON Lines reader such as
// jq takes): std::runtime_error naming the first line that is not.
inline std::vector<nlohmann::json> whole_json_lines(const std::string& out) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    const auto parsed = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!parsed.is_object()) throw std::runtime_error("not a JSON object: \"" + line + "\"");
    lines.push_back(parsed);
  }
  return lines;
}

// The largest resident set of any child process waited for so far, in MiB.
inline double max_child_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace dtmf::test_support
