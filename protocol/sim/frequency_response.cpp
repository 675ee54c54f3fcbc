#include "sim/frequency_response.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "sim/number_text.h"
#include "sim/real_fft.h"
#include "units/decibels.h"

namespace dtmf::sim {

namespace {

constexpr std::size_t kDesignGrid = 16384;  // frequency-sampling grid: 2.9 Hz at 48 kHz
constexpr double kMinGainDb = -120, kMaxGainDb = 40;

struct Preset {
  const char* name;
  std::vector<std::pair<double, double>> points;
};

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"flat", {}},
      {"cheap-mic", {{20, -30}, {50, -15}, {100, -3}, {200, 0}, {5000, 0}, {10000, -3}, {16000, -12}, {20000, -20}}},
      {"small-speaker",
       {{100, -24}, {200, -12}, {400, -3}, {700, 0}, {3000, 3}, {6000, 0}, {12000, -6}, {16000, -15}, {20000, -25}}},
  };
  return all;
}

std::vector<std::pair<double, double>> checked(std::vector<std::pair<double, double>> points, const std::string& what) {
  if (points.empty())
    throw std::invalid_argument(what + " holds no breakpoints: give Hz:dB pairs such as 200:0,16000:-12");
  std::sort(points.begin(), points.end());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [hz, db] = points[i];
    if (!std::isfinite(hz) || hz <= 0) {
      throw std::invalid_argument(what + ": frequency " + number_text(hz) + " Hz must be above 0");
    }
    if (!std::isfinite(db) || db < kMinGainDb || db > kMaxGainDb) {
      throw std::invalid_argument(what + ": gain " + number_text(db) + " dB at " + number_text(hz) +
                                  " Hz must lie between -120 and +40 dB");
    }
    if (i > 0 && hz == points[i - 1].first) {
      throw std::invalid_argument(what + ": " + number_text(hz) + " Hz is given twice");
    }
  }
  return points;
}

// "Hz:dB" pairs separated by commas, semicolons, spaces or new lines ('#' starts a comment).
std::vector<std::pair<double, double>> parse_points(const std::string& text, const std::string& what) {
  std::string cleaned;
  bool comment = false;
  for (char c : text) {
    if (c == '#') comment = true;
    if (c == '\n') comment = false;
    cleaned += comment || c == ',' || c == ';' || c == '\t' || c == '\r' ? ' ' : c;
  }
  std::istringstream in(cleaned);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    std::string hz = tokens[i], db;
    if (const auto colon = hz.find(':'); colon != std::string::npos) {
      db = hz.substr(colon + 1);
      hz.resize(colon);
    } else if (i + 1 < tokens.size()) {
      db = tokens[++i];  // "Hz dB" on one line of a file
    }
    try {
      std::size_t end_hz = 0, end_db = 0;
      const double f = std::stod(hz, &end_hz), g = std::stod(db, &end_db);
      if (end_hz != hz.size() || end_db != db.size()) throw std::invalid_argument("trailing text");
      points.emplace_back(f, g);
    } catch (const std::exception&) {
      throw std::invalid_argument(what + ": '" + tokens[i] + "' is not a Hz:dB pair (e.g. 16000:-12)");
    }
  }
  return checked(std::move(points), what);
}

}  // namespace

std::string response_preset_names() {
  std::string names;
  for (const auto& p : presets()) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

FrequencyResponse response_preset(const std::string& name) {
  for (const auto& p : presets()) {
    if (name == p.name) return {p.name, p.points};
  }
  throw std::invalid_argument("no frequency response preset '" + name + "': the presets are " +
                              response_preset_names());
}

FrequencyResponse parse_response(const std::string& text) {
  for (const auto& p : presets()) {
    if (text == p.name) return {p.name, p.points};
  }
  if (!text.empty() && (std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '.') &&
      text.find(':') != std::string::npos) {
    return {text, parse_points(text, "frequency response '" + text + "'")};
  }
  std::ifstream file(text);
  if (!file) {
    throw std::invalid_argument("frequency response '" + text + "' is neither a preset (" + response_preset_names() +
                                "), breakpoints (Hz:dB,... e.g. 200:0,16000:-12) nor a readable file of them");
  }
  std::stringstream contents;
  contents << file.rdbuf();
  return {text, parse_points(contents.str(), "frequency response file '" + text + "'")};
}

double response_gain_db(const FrequencyResponse& response, double frequency_hz) {
  const auto& p = response.points_db;
  if (p.empty()) return 0;
  if (frequency_hz <= p.front().first) return p.front().second;
  if (frequency_hz >= p.back().first) return p.back().second;
  const auto above = std::upper_bound(p.begin(), p.end(), std::make_pair(frequency_hz, -1e300));
  const auto below = above - 1;
  const double t = std::log(frequency_hz / below->first) / std::log(above->first / below->first);
  return below->second + t * (above->second - below->second);
}

std::vector<float> response_fir(const FrequencyResponse& response, int sample_rate_hz) {
  if (response.flat()) return {1.0f};
  // Zero-phase design on a fine grid: the inverse FFT of real gains is even around 0.
  const RealFft fft(kDesignGrid);
  FftBins bins(fft.bins());
  for (std::size_t k = 0; k < bins.size(); ++k) {
    const double f = static_cast<double>(k) * sample_rate_hz / static_cast<double>(kDesignGrid);
    bins[k] = static_cast<float>(units::amplitude_ratio_from_db(response_gain_db(response, f)) / kDesignGrid);
  }
  FftReal impulse(kDesignGrid);
  fft.inverse(bins.data(), impulse.data());
  constexpr int half = (kResponseTaps - 1) / 2;
  std::vector<float> taps(kResponseTaps);
  for (int n = -half; n <= half; ++n) {
    const double x = static_cast<double>(n + half) / (kResponseTaps - 1);  // 0 .. 1 over the window
    const double blackman = 0.42 - 0.5 * std::cos(2 * std::numbers::pi * x) + 0.08 * std::cos(4 * std::numbers::pi * x);
    const auto index = static_cast<std::size_t>((n + static_cast<int>(kDesignGrid)) % static_cast<int>(kDesignGrid));
    taps[static_cast<std::size_t>(n + half)] = static_cast<float>(impulse[index] * blackman);
  }
  return taps;
}

}  // namespace dtmf::sim
