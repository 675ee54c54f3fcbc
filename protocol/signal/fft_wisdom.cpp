#include "signal/fft_wisdom.h"

#include <fftw3.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>

#include "signal/spectrum.h"

namespace dtmf::signal {

namespace {

std::string& wisdom_file() {  // guarded by planner_mutex()
  static std::string path;
  return path;
}

std::string from_environment(const char* name, const char* suffix) {
  const char* value = std::getenv(name);
  if (!value || !*value) return {};
  return std::string(value) + suffix;
}

}  // namespace

std::string fft_wisdom_default_file() {
  for (const auto& [name, suffix] : {std::pair{"DTMF_FFTW_WISDOM", ""}, std::pair{"CACHE_DIRECTORY", "/fftw-wisdom"},
                                     std::pair{"XDG_CACHE_HOME", "/dtmf-teleop/fftw-wisdom"},
                                     std::pair{"HOME", "/.cache/dtmf-teleop/fftw-wisdom"}}) {
    if (auto path = from_environment(name, suffix); !path.empty()) return path == "none" ? "" : path;
  }
  return {};
}

void use_fft_wisdom_file(const std::string& path) {
  std::lock_guard lock(planner_mutex());
  wisdom_file() = path;
  // A missing or unreadable file is no wisdom yet (fftwf_import_wisdom_from_filename fails).
  if (!path.empty()) fftwf_import_wisdom_from_filename(path.c_str());
}

void fft_wisdom_learned() {
  const std::string& path = wisdom_file();
  if (path.empty()) return;
  std::error_code ignored;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ignored);
  // Another process may save at the same time: each writes its own temporary, and rename()
  // replaces the file whole, so a reader sees one complete file or the other.
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  if (fftwf_export_wisdom_to_filename(temporary.c_str())) {
    std::filesystem::rename(temporary, path, ignored);
  }
  std::filesystem::remove(temporary, ignored);
}

}  // namespace dtmf::signal
