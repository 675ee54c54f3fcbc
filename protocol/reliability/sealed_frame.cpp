#include "reliability/sealed_frame.h"

namespace dtmf::reliability {

namespace {
constexpr int kSymbolBits = 5;
constexpr int kCheckedBits = kSealedFrameBits - kSealedCheckBits;  // 72
constexpr WideBits mask(int bits) { return (WideBits{1} << bits) - 1; }
// Whether a decode left the parity a refusal needs for detection (sealed_frame.h).
constexpr bool kept_for_refusal(DecodedSymbols how) {
  return 2 * how.errors + how.erasures <= kSealedSymbols - kSealedDataSymbols - kSealedRefusalReserveSymbols;
}
}  // namespace

std::uint8_t crc8_autosar(WideBits bits, int width) {
  std::uint8_t crc = 0xFF;
  for (int i = width - 1; i >= 0; --i) {
    const bool bit = (bits >> i) & 1u;
    const bool top = (crc >> 7) & 1u;
    crc = static_cast<std::uint8_t>(crc << 1);
    if (bit != top) crc ^= 0x2F;
  }
  return static_cast<std::uint8_t>(crc ^ 0xFF);
}

FrameBits sealed_frame_pack(const SealedFrame& f) {
  WideBits body = static_cast<WideBits>(f.address & 7u) << 1 | static_cast<WideBits>(f.form);
  if (f.form == SealedForm::Command) {
    body = body << kSealedCounterLowBits | (f.counter & mask(kSealedCounterLowBits));
    body = body << 27 | (f.payload & mask(27));
  } else {
    body = body << kSealedSyncCounterBits | (f.counter & mask(kSealedSyncCounterBits));
  }
  body = body << kSealedMacBits | f.mac;
  return sealed_with_check(body);
}

FrameBits sealed_with_check(WideBits body) {
  return FrameBits::wide(body << kSealedCheckBits | crc8_autosar(body, kCheckedBits));
}

std::optional<WideBits> sealed_checked_body(FrameBits bits) {
  const WideBits v = bits.value();
  if (v >> kSealedFrameBits) return std::nullopt;
  const WideBits body = v >> kSealedCheckBits;
  if (crc8_autosar(body, kCheckedBits) != static_cast<std::uint8_t>(v & 0xFF)) return std::nullopt;
  return body;
}

std::optional<SealedFrame> sealed_frame_unpack(FrameBits bits) {
  const auto checked = sealed_checked_body(bits);
  if (!checked) return std::nullopt;
  const WideBits body = *checked;
  SealedFrame f;
  f.mac = static_cast<std::uint32_t>(body & mask(kSealedMacBits));
  const WideBits head = body >> kSealedMacBits;  // 40 bits: address, form, counter [, payload]
  f.address = static_cast<std::uint8_t>((head >> 37) & 7u);
  f.form = ((head >> 36) & 1u) ? SealedForm::Sync : SealedForm::Command;
  if (f.form == SealedForm::Command) {
    f.counter = static_cast<std::uint64_t>((head >> 27) & mask(kSealedCounterLowBits));
    f.payload = static_cast<std::uint32_t>(head & mask(27));
  } else {
    f.counter = static_cast<std::uint64_t>(head & mask(kSealedSyncCounterBits));
  }
  return f;
}

const ReedSolomon& sealed_code() {
  static const ReedSolomon code(kSymbolBits, kSealedSymbols, kSealedDataSymbols);
  return code;
}

SealedSymbols sealed_frame_symbols(FrameBits bits) {
  std::array<std::uint8_t, kSealedDataSymbols> data{};
  for (int i = 0; i < kSealedDataSymbols; ++i) {
    data[static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>((bits.value() >> (kSymbolBits * (kSealedDataSymbols - 1 - i))) & mask(kSymbolBits));
  }
  SealedSymbols symbols{};
  sealed_code().encode(data, symbols);
  return symbols;
}

FrameBits sealed_frame_data_bits(std::span<const std::uint8_t> data_symbols) {
  WideBits bits = 0;
  for (int i = 0; i < kSealedDataSymbols; ++i) bits = bits << kSymbolBits | data_symbols[static_cast<std::size_t>(i)];
  return FrameBits::wide(bits);
}

SealedDecode decode_sealed(std::span<const SymbolReading, kSealedSymbols> readings, int max_erasures,
                           const SealedCheck& authentic, int chase_tones) {
  std::array<std::uint8_t, kSealedDataSymbols> data{};
  std::optional<SealedFrame> frame;
  SealedDecode result;
  const auto decoded = chase_symbols(readings, sealed_code(), max_erasures, kSealedReserveSymbols, chase_tones, data,
                                     [&](std::span<const std::uint8_t> d, DecodedSymbols how) {
                                       const FrameBits bits = sealed_frame_data_bits(d);
                                       frame = sealed_frame_unpack(bits);
                                       if (!frame) return false;
                                       if (authentic(bits)) return true;
                                       if (!result.intact && kept_for_refusal(how)) {
                                         result.intact = DecodedSealed{*frame, bits, how.erasures, how.errors};
                                       }
                                       return false;
                                     });
  if (decoded)
    result.authentic = DecodedSealed{*frame, sealed_frame_data_bits(data), decoded->erasures, decoded->errors};
  return result;
}

FrameBits read_sealed_bits(std::span<const SymbolReading, kSealedSymbols> readings) {
  std::array<std::uint8_t, kSealedDataSymbols> data{};
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = readings[i].symbol;
  return sealed_frame_data_bits(data);
}

}  // namespace dtmf::reliability
