#include "reliability/frame_code.h"

namespace dtmf::reliability {

const ReedSolomon& frame_code() {
  static const ReedSolomon code(kCodeSymbolBits, kCodeSymbols, kCodeDataSymbols);
  return code;
}

std::optional<DecodedFrame> decode_frame(std::span<const SymbolReading, kCodeSymbols> readings, int max_erasures,
                                         int chase_tones) {
  std::array<std::uint8_t, kCodeDataSymbols> data{};
  std::optional<CommandFrame> frame;
  const auto decoded = chase_symbols(readings, frame_code(), max_erasures, kCodeReserveSymbols, chase_tones, data,
                                     [&](std::span<const std::uint8_t> d, DecodedSymbols) {
                                       return (frame = command_frame_unpack(command_frame_data_bits(d))).has_value();
                                     });
  if (!decoded) return std::nullopt;
  return DecodedFrame{*frame, command_frame_data_bits(data), decoded->erasures, decoded->errors};
}

std::uint64_t read_bits(std::span<const SymbolReading, kCodeSymbols> readings) {
  std::array<std::uint8_t, kCodeDataSymbols> data{};
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = readings[i].symbol;
  return command_frame_data_bits(data);
}

}  // namespace dtmf::reliability
