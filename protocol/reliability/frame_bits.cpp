#include "reliability/frame_bits.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::reliability {

std::string FrameBits::bit_string(int width) const {
  std::string out(static_cast<std::size_t>(width), '0');
  for (int i = 0; i < width && i < 128; ++i) {
    if ((value_ >> i) & 1u) out[static_cast<std::size_t>(width - 1 - i)] = '1';
  }
  return out;
}

std::string FrameBits::decimal() const {
  if (value_ == 0) return "0";
  std::string out;
  for (WideBits v = value_; v != 0; v /= 10) out.push_back(static_cast<char>('0' + static_cast<int>(v % 10)));
  std::reverse(out.begin(), out.end());
  return out;
}

FrameBits FrameBits::parse_decimal(const std::string& digits) {
  if (digits.empty() || digits.size() > 39)
    throw std::invalid_argument("not a frame number: '" + digits.substr(0, 40) + "'");
  WideBits v = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') throw std::invalid_argument("not a frame number: '" + digits.substr(0, 40) + "'");
    const WideBits next = v * 10 + static_cast<unsigned>(c - '0');
    if (next / 10 != v) throw std::invalid_argument("frame number out of range: '" + digits + "'");
    v = next;
  }
  return wide(v);
}

}  // namespace dtmf::reliability
