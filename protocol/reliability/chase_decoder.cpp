#include "reliability/chase_decoder.h"

#include <algorithm>
#include <numeric>

namespace dtmf::reliability {

std::optional<ChasedFrame> chase_decode(const SymbolReading& reading, int chase_symbols) {
  Symbols symbols = reading.symbols;
  if (const auto frame = unpack(from_symbols(symbols))) return ChasedFrame{*frame, from_symbols(symbols), 0};

  std::array<int, kCommandSymbols> order{};
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return reading.certainty[static_cast<std::size_t>(a)] < reading.certainty[static_cast<std::size_t>(b)];
  });
  const int tries = std::min(chase_symbols, kCommandSymbols);
  for (int i = 0; i < tries; ++i) {
    const auto at = static_cast<std::size_t>(order[static_cast<std::size_t>(i)]);
    if (reading.runner_up[at] == reading.symbols[at]) continue;
    symbols[at] = reading.runner_up[at];
    const std::uint64_t bits = from_symbols(symbols);
    if (const auto frame = unpack(bits)) return ChasedFrame{*frame, bits, 1};
    symbols[at] = reading.symbols[at];
  }
  return std::nullopt;
}

}  // namespace dtmf::reliability
