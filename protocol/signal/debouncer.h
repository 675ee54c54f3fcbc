// Signal layer, part 6: the debouncer that turns repeated detections into one event.
//
// Seed section 8: a symbol (a chord's 16 bits, or ACK/NACK) passes after `min_detections`
// detections of it within `window_ms`; the symbol that passed is then ignored for
// `lockout_ms` (its detections in that time are dropped, so the tail of a long chord cannot
// pass it twice); any other symbol passes as soon as it has its own detections.
// Pure logic: times are the caller's (milliseconds of audio); nothing is allocated.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "profile/link_profile.h"

namespace dtmf::signal {

class Debouncer {
 public:
  struct Pass {
    std::uint32_t symbol;
    double first_detection_ms;  // the earliest detection that counted
    double pass_ms;             // the detection that completed it
  };

  explicit Debouncer(const DebounceParams& params);

  std::optional<Pass> on_detection(std::uint32_t symbol, double t_ms);
  void reset();

 private:
  struct Detection {
    std::uint32_t symbol;
    double t_ms;
  };
  static constexpr std::size_t kCapacity = 64;

  DebounceParams params_;
  std::array<Detection, kCapacity> recent_{};  // ring buffer, oldest at head_
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::optional<std::uint32_t> locked_symbol_;
  double locked_until_ms_ = 0;
};

}  // namespace dtmf::signal
