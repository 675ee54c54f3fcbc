#include "reliability/reply_code.h"

#include <algorithm>
#include <random>
#include <vector>

namespace dtmf::reliability {

namespace {

constexpr int kReplies = 17;  // ACK(0..15), then NACK
constexpr int kNack = 16;
constexpr int kMinDistance = 7;

int distance(const ReplyTones& a, const ReplyTones& b) {
  int d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d += a[i] != b[i] ? 1 : 0;
  return d;
}

// The 17 words, found once by a seeded search (the same on every machine: mt19937's output is
// fixed by the standard): each new candidate is kept when it repeats no band's tone across
// its chords and differs from every word kept in at least kMinDistance tones. Random words
// differ in 9 of the 12 on average, so the search ends after some dozens of candidates.
const std::array<ReplyTones, kReplies>& codewords() {
  static const auto words = [] {
    std::mt19937 rng(20261125);
    std::vector<ReplyTones> kept;
    while (kept.size() < kReplies) {
      ReplyTones w{};
      for (auto& t : w) t = static_cast<std::uint8_t>(rng() % kReplyToneValues);
      bool far = true;
      for (std::size_t b = 0; b < kReplyBandsPerChord; ++b) far = far && w[b] != w[b + kReplyBandsPerChord];
      for (const auto& k : kept) far = far && distance(w, k) >= kMinDistance;
      if (far) kept.push_back(w);
    }
    std::array<ReplyTones, kReplies> out{};
    std::copy(kept.begin(), kept.end(), out.begin());
    return out;
  }();
  return words;
}

}  // namespace

ReplyTones reply_codeword(const NamedReply& reply) {
  return codewords()[static_cast<std::size_t>(reply.ack ? (reply.sequence & 15) : kNack)];
}

std::optional<NamedReply> read_reply(const ReplyReading& reading, int tones_needed) {
  for (int r = 0; r < kReplies; ++r) {
    const ReplyTones& word = codewords()[static_cast<std::size_t>(r)];
    int agree = 0;
    for (std::size_t t = 0; t < word.size(); ++t) agree += reading[t] == word[t] ? 1 : 0;
    if (agree >= tones_needed)
      return r == kNack ? NamedReply{false, 0} : NamedReply{true, static_cast<std::uint8_t>(r)};
  }
  return std::nullopt;
}

}  // namespace dtmf::reliability
