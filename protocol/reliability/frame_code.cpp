#include "reliability/frame_code.h"

#include <algorithm>
#include <numeric>

namespace dtmf::reliability {

const ReedSolomon& frame_code() {
  static const ReedSolomon code(kCodeSymbolBits, kCodeSymbols, kCodeDataSymbols);
  return code;
}

std::optional<DecodedFrame> decode_frame(std::span<const SymbolReading, kCodeSymbols> readings, int max_erasures) {
  std::array<std::uint8_t, kCodeSymbols> received{};
  std::array<int, kCodeSymbols> order{};
  std::iota(order.begin(), order.end(), 0);
  // Unheard tones first, then the heard ones from the least certain. An insertion sort:
  // stable, and unlike std::stable_sort it allocates nothing (this runs every frame).
  const auto before = [&](int a, int b) {
    const auto& x = readings[static_cast<std::size_t>(a)];
    const auto& y = readings[static_cast<std::size_t>(b)];
    if (x.heard != y.heard) return !x.heard;
    return x.certainty < y.certainty;
  };
  for (std::size_t i = 1; i < order.size(); ++i) {
    const int v = order[i];
    std::size_t j = i;
    for (; j > 0 && before(v, order[j - 1]); --j) order[j] = order[j - 1];
    order[j] = v;
  }
  int unheard = 0;
  for (std::size_t i = 0; i < kCodeSymbols; ++i) {
    received[i] = readings[i].symbol;
    unheard += readings[i].heard ? 0 : 1;
  }
  const int limit = std::min(max_erasures, kCodeSymbols - kCodeDataSymbols - kCodeReserveSymbols);
  for (int erased = unheard; erased <= limit; ++erased) {
    std::array<std::uint8_t, kCodeDataSymbols> data{};
    const auto errors = frame_code().decode(
        received, std::span<const int>(order.data(), static_cast<std::size_t>(erased)), data, kCodeReserveSymbols);
    if (!errors) continue;
    const std::uint64_t bits = data_bits(data);
    if (const auto frame = unpack(bits)) return DecodedFrame{*frame, bits, erased, *errors};
  }
  return std::nullopt;
}

std::uint64_t read_bits(std::span<const SymbolReading, kCodeSymbols> readings) {
  std::array<std::uint8_t, kCodeDataSymbols> data{};
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = readings[i].symbol;
  return data_bits(data);
}

}  // namespace dtmf::reliability
