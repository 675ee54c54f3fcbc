// Reliability layer: decoding a Reed–Solomon codeword from tones heard with unequal
// certainty — the one decoder behind every frame of the fast profile (frame_code.h,
// sealed_frame.h).
//
// The listener reads each tone as a symbol with a certainty (how far its bin stood above the
// runner-up) and a flag for tones it could not hear at all. Decoding tries the codeword with
// the unheard tones erased, then with the least certain heard tones erased too, one more at a
// time, up to `max_erasures`; the first data whose `check` holds (a CRC) is the frame. When
// more tones went unheard than may be erased (in a reverberant room a tone that rose with its
// chord often stands too little over the band's other bins to count as heard, yet reads
// right), the least certain of them are erased, max_erasures, then two fewer at a time: each
// two erasures given back let the code correct one more wrong tone among the rest. Tones that
// did not rise with their chord come first among those erased. (A frame's reverberant tail
// reads every symbol right and rises nowhere: the receive path keeps it from passing as the
// frame again, link/hop_frame_path.h.) The
// code keeps `reserve` parity symbols for detection (2 * errors + erasures <= parity -
// reserve): pushed to its limit, it turns noise into some codeword. chase_symbols() goes on
// where that fails, swapping the least certain tones for their bands' runner-ups. Pure logic;
// allocates nothing (it runs in the robot's receive path).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <optional>
#include <span>

#include "reliability/reed_solomon.h"

namespace dtmf::reliability {

struct SymbolReading {
  std::uint8_t symbol = 0;  // the strongest tone of its band
  float certainty = 1;      // its power over the runner-up's (>= 1)
  bool heard = true;        // false: erase it
  bool risen = true;        // false: it did not start with its chord (a tail): never trusted
  int runner_up = -1;       // the band's second strongest tone, when the listener knows it
};

struct DecodedSymbols {
  int erasures = 0;  // symbols erased to decode it
  int errors = 0;    // symbols corrected beyond those
};

inline constexpr int kMaxCodeSymbols = 32;

// Sorts symbol indices by `before`: an insertion sort, stable, and unlike std::stable_sort
// it allocates nothing (both decoders below run in the robot's receive path).
template <typename Before>
void sort_symbols(std::span<int> indices, Before&& before) {
  for (std::size_t i = 1; i < indices.size(); ++i) {
    const int v = indices[i];
    std::size_t j = i;
    for (; j > 0 && before(v, indices[j - 1]); --j) indices[j] = indices[j - 1];
    indices[j] = v;
  }
}

// `check(data, how)` says whether the data symbols decoded are a frame (`how`: the erasures
// and corrections it took, which leave 2 * errors + erasures of the parity spent); the data
// of the first that is stays in `data`.
template <typename Check>
std::optional<DecodedSymbols> decode_symbols(std::span<const SymbolReading> readings, const ReedSolomon& code,
                                             int max_erasures, int reserve, std::span<std::uint8_t> data,
                                             Check&& check) {
  const std::size_t n = readings.size();
  std::array<std::uint8_t, kMaxCodeSymbols> received{};
  std::array<int, kMaxCodeSymbols> order{};
  std::iota(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), 0);
  // Unheard tones first, then the heard ones from the least certain.
  sort_symbols(std::span<int>(order.data(), n), [&](int a, int b) {
    const auto& x = readings[static_cast<std::size_t>(a)];
    const auto& y = readings[static_cast<std::size_t>(b)];
    if (x.risen != y.risen) return !x.risen;
    if (x.heard != y.heard) return !x.heard;
    return x.certainty < y.certainty;
  });
  int unheard = 0;
  for (std::size_t i = 0; i < n; ++i) {
    received[i] = readings[i].symbol;
    unheard += readings[i].heard ? 0 : 1;
  }
  const int limit = std::min(max_erasures, code.parity() - reserve);
  const auto attempt = [&](int erased) -> std::optional<DecodedSymbols> {
    const auto errors =
        code.decode(std::span<const std::uint8_t>(received.data(), n),
                    std::span<const int>(order.data(), static_cast<std::size_t>(erased)), data, reserve);
    if (!errors) return std::nullopt;
    const DecodedSymbols how{erased, *errors};
    if (check(std::span<const std::uint8_t>(data), how)) return how;
    return std::nullopt;
  };
  if (unheard <= limit) {
    for (int erased = unheard; erased <= limit; ++erased) {
      if (const auto d = attempt(erased)) return d;
    }
    return std::nullopt;
  }
  for (int erased = limit; erased >= 0; erased -= 2) {
    if (const auto d = attempt(erased)) return d;
  }
  return std::nullopt;
}

// Chase's second algorithm after the erasures: the `doubted` least certain heard symbols are
// swapped for their bands' runner-ups in every combination, each decoded with the unheard
// erased. A misread tone is most often its band's runner-up, and a swap that is right costs no
// parity where an erasure costs one. Each attempt is one more chance for noise to pass `check`,
// so each keeps one parity symbol more than `reserve` for detection (docs/protocol.md, `chase_tones`).
template <typename Check>
std::optional<DecodedSymbols> chase_symbols(std::span<const SymbolReading> readings, const ReedSolomon& code,
                                            int max_erasures, int reserve, int doubted, std::span<std::uint8_t> data,
                                            Check&& check) {
  if (const auto d = decode_symbols(readings, code, max_erasures, reserve, data, check)) return d;
  const std::size_t n = readings.size();
  std::array<std::uint8_t, kMaxCodeSymbols> received{};
  std::array<int, kMaxCodeSymbols> erasures{};
  std::array<int, kMaxCodeSymbols> swaps{};
  int unheard = 0;
  for (std::size_t i = 0; i < n; ++i) {
    received[i] = readings[i].symbol;
    if (!readings[i].heard || !readings[i].risen) erasures[static_cast<std::size_t>(unheard++)] = static_cast<int>(i);
  }
  const int swap_reserve = reserve + 1;  // over GF(32): 32 times fewer chances for noise a try
  // (More unheard than may be erased: the first of them are, the rest stay as read.)
  const int erased = std::min(unheard, std::min(max_erasures, code.parity() - swap_reserve));
  // The heard symbols that have a runner-up, least certain first; the first `doubted` are swapped.
  int eligible = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = readings[i];
    if (r.heard && r.risen && r.runner_up >= 0) swaps[static_cast<std::size_t>(eligible++)] = static_cast<int>(i);
  }
  sort_symbols(std::span<int>(swaps.data(), static_cast<std::size_t>(eligible)), [&](int a, int b) {
    return readings[static_cast<std::size_t>(a)].certainty < readings[static_cast<std::size_t>(b)].certainty;
  });
  const int swappable = std::min(eligible, doubted);
  for (unsigned mask = 1; mask < (1u << swappable); ++mask) {
    for (int k = 0; k < swappable; ++k) {
      const auto& r = readings[static_cast<std::size_t>(swaps[static_cast<std::size_t>(k)])];
      received[static_cast<std::size_t>(swaps[static_cast<std::size_t>(k)])] =
          (mask >> k) & 1u ? static_cast<std::uint8_t>(r.runner_up) : r.symbol;
    }
    const auto errors =
        code.decode(std::span<const std::uint8_t>(received.data(), n),
                    std::span<const int>(erasures.data(), static_cast<std::size_t>(erased)), data, swap_reserve);
    if (!errors) continue;
    const DecodedSymbols how{erased, *errors};
    if (check(std::span<const std::uint8_t>(data), how)) return how;
  }
  return std::nullopt;
}

}  // namespace dtmf::reliability
