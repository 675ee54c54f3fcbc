// Reliability layer: a frame's bits, right-aligned, up to 128 of them — wide enough for every
// frame format (the seed's 16, the fast profile's 50, its authenticated 80).
//
// A value type: built from a 64-bit frame implicitly, or from a 128-bit one; compared,
// printed as bits or as a decimal number (the database keeps frames as numeric). Pure.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace dtmf::reliability {

__extension__ typedef unsigned __int128 WideBits;  // GCC's 128-bit integer (Debian's g++ and clang)

class FrameBits {
 public:
  constexpr FrameBits() = default;
  constexpr FrameBits(std::uint64_t bits) : value_(bits) {}  // NOLINT: every narrower frame is one
  static constexpr FrameBits wide(WideBits bits) {
    FrameBits f;
    f.value_ = bits;
    return f;
  }
  constexpr WideBits value() const { return value_; }
  constexpr std::uint64_t low64() const { return static_cast<std::uint64_t>(value_); }
  constexpr bool fits64() const { return (value_ >> 64) == 0; }
  friend constexpr bool operator==(FrameBits a, FrameBits b) { return a.value_ == b.value_; }

  // "1011001011011101": the low `width` bits, most significant first.
  std::string bit_string(int width) const;
  // "2861": the value in decimal.
  std::string decimal() const;
  // The value of a decimal string of digits; std::invalid_argument otherwise.
  static FrameBits parse_decimal(const std::string& digits);

 private:
  WideBits value_ = 0;
};

}  // namespace dtmf::reliability

template <>
struct std::hash<dtmf::reliability::FrameBits> {
  std::size_t operator()(dtmf::reliability::FrameBits f) const noexcept {
    return std::hash<std::uint64_t>{}(f.low64() ^
                                      (static_cast<std::uint64_t>(f.value() >> 64) * 0x9E3779B97F4A7C15ull));
  }
};
