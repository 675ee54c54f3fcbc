// Physical layer: numbers in messages, as a person writes them ("0.97", "7", "1e-05"),
// not as std::to_string does ("0.970000").
#pragma once

#include <cstdio>
#include <string>

namespace dtmf::sim {

inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace dtmf::sim
