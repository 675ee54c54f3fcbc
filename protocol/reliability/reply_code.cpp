#include "reliability/reply_code.h"

#include <algorithm>

#include "reliability/reed_solomon.h"

namespace dtmf::reliability {

namespace {

constexpr int kReplies = 17;  // ACK(0..15), then NACK
constexpr int kNack = 16;

// The first 17 codewords of RS(4, 2) over GF(8), in data order, that have no tone 0.
const std::array<ReplyTones, kReplies>& codewords() {
  static const auto words = [] {
    const ReedSolomon code(3, 4, 2);
    std::array<ReplyTones, kReplies> out{};
    int found = 0;
    for (int data = 0; data < 64 && found < kReplies; ++data) {
      const std::array<std::uint8_t, 2> d{static_cast<std::uint8_t>(data >> 3), static_cast<std::uint8_t>(data & 7)};
      const auto word = code.encode(d);
      if (std::find(word.begin(), word.end(), 0) != word.end()) continue;
      std::copy(word.begin(), word.end(), out[static_cast<std::size_t>(found++)].begin());
    }
    return out;
  }();
  return words;
}

}  // namespace

ReplyTones reply_codeword(const NamedReply& reply) {
  return codewords()[static_cast<std::size_t>(reply.ack ? (reply.sequence & 15) : kNack)];
}

std::optional<NamedReply> read_reply(const std::array<int, 4>& tones, int bands_needed) {
  for (int r = 0; r < kReplies; ++r) {
    const ReplyTones& word = codewords()[static_cast<std::size_t>(r)];
    int agree = 0;
    for (std::size_t b = 0; b < 4; ++b) agree += tones[b] == word[b] ? 1 : 0;
    if (agree >= bands_needed)
      return r == kNack ? NamedReply{false, 0} : NamedReply{true, static_cast<std::uint8_t>(r)};
  }
  return std::nullopt;
}

}  // namespace dtmf::reliability
