// The fast profile's reliability layer: the 50-bit frame, its Reed-Solomon code and the
// decoding of tones heard with unequal certainty, the frame gate (one verdict per frame),
// the sequence filter (no double execution) and the reply code.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "reliability/command_frame.h"
#include "reliability/frame_code.h"
#include "reliability/frame_gate.h"
#include "reliability/reply_code.h"
#include "reliability/sequence_filter.h"

using namespace dtmf::reliability;

namespace {
std::array<SymbolReading, kCodeSymbols> readings_of(const CodeSymbols& symbols) {
  std::array<SymbolReading, kCodeSymbols> r{};
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = {symbols[i], 100.0f, true};
  return r;
}
}  // namespace

TEST(Crc16, MatchesCcittFalseReferenceValues) {
  // binascii.crc_hqx(data, 0xFFFF) in Python computes CRC-16/CCITT-FALSE.
  EXPECT_EQ(crc16(0x12345678, 32), 0x30EC);
  EXPECT_EQ(crc16(0x3132333435363738ull, 64), 0xA12B);  // "12345678"
}

TEST(CommandFrame, PacksAddressSequencePayloadAndCrcAndUnpacksThem) {
  const CommandFrame f{5, 11, 0x5ABCDEF};
  const std::uint64_t bits = command_frame_pack(f);
  EXPECT_EQ(bits >> 47, 5u);
  EXPECT_EQ((bits >> 43) & 0xF, 11u);
  EXPECT_EQ((bits >> 16) & kFramePayloadMask, 0x5ABCDEFu);
  EXPECT_EQ(bits & 0xFFFF, crc16(bits >> 16, 34));
  EXPECT_EQ(command_frame_unpack(bits), f);
  EXPECT_FALSE(command_frame_unpack(bits ^ (1ull << 30))) << "a flipped bit fails the CRC";
  EXPECT_FALSE(command_frame_unpack(0).has_value()) << "the all-zero frame is not a codeword";
  const CodeSymbols symbols = command_frame_symbols(bits);
  EXPECT_EQ(command_frame_data_bits(std::span<const std::uint8_t>(symbols).first(kCodeDataSymbols)), bits);
}

// RS(16, 10) with two parity symbols kept for detection: one or two wrong tones anywhere,
// or up to four unheard ones, and the frame comes back; three wrong tones are refused
// (the code could correct them, but then noise would "decode" far too often).
TEST(FrameCode, CorrectsTwoWrongTonesOrFourUnheardAndRefusesThree) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    const CommandFrame f{0, static_cast<std::uint8_t>(rng() & 15),
                         static_cast<std::uint32_t>(rng() & kFramePayloadMask)};
    const std::uint64_t bits = command_frame_pack(f);
    const CodeSymbols clean = command_frame_symbols(bits);
    std::array<int, kCodeSymbols> order{};
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    auto wrong = [&](int count) {
      auto r = readings_of(clean);
      for (int i = 0; i < count; ++i) {
        auto& s = r[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
        s.symbol = static_cast<std::uint8_t>((s.symbol + 1 + rng() % 31) % 32);
      }
      return r;
    };
    const auto two = decode_frame(wrong(2), 4);
    ASSERT_TRUE(two) << trial;
    EXPECT_EQ(two->frame, f);
    EXPECT_EQ(two->errors, 2);
    auto unheard = wrong(4);
    for (int i = 0; i < 4; ++i) unheard[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])].heard = false;
    const auto four = decode_frame(unheard, 4);
    ASSERT_TRUE(four) << trial;
    EXPECT_EQ(four->frame, f);
    EXPECT_EQ(four->erasures, 4);
    EXPECT_FALSE(decode_frame(wrong(3), 0)) << "three errors and no erasures allowed";
  }
}

// The least certain tones are erased first: three wrong tones are too many errors, but
// when they were the least certain, erasing two of them leaves one error to correct. The
// same three wrong tones heard with confidence, and right tones doubted, are refused.
TEST(FrameCode, ErasesTheLeastCertainTonesFirst) {
  const CommandFrame f{0, 3, 0x1234567};
  const CodeSymbols clean = command_frame_symbols(command_frame_pack(f));
  auto doubted_wrong = readings_of(clean);
  auto doubted_right = readings_of(clean);
  for (std::size_t i : {2u, 9u, 13u}) {
    for (auto* r : {&doubted_wrong, &doubted_right}) (*r)[i].symbol = static_cast<std::uint8_t>((clean[i] + 5) % 32);
    doubted_wrong[i].certainty = 1.1f;  // barely over its runner-up
  }
  for (std::size_t i : {0u, 5u, 7u, 11u}) doubted_right[i].certainty = 1.05f;
  const auto decoded = decode_frame(doubted_wrong, 4);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->frame, f);
  EXPECT_EQ(decoded->erasures, 2);
  EXPECT_EQ(decoded->errors, 1);
  EXPECT_FALSE(decode_frame(doubted_right, 4));
}

// Three tones misread, barely over their bands' runner-ups, which were the tones sent, and a
// fourth misread with confidence: erasing the three leaves no parity to correct the fourth,
// but swapping them for their runner-ups (Chase) costs no parity at all.
TEST(FrameCode, SwappingDoubtedTonesForTheirRunnerUpsCorrectsWhatErasingCannot) {
  const CommandFrame f{0, 9, 0x2abcdef};
  const CodeSymbols clean = command_frame_symbols(command_frame_pack(f));
  auto r = readings_of(clean);
  for (std::size_t i : {1u, 4u, 8u}) {
    r[i].symbol = static_cast<std::uint8_t>((clean[i] + 7) % 32);
    r[i].certainty = 1.2f;
    r[i].runner_up = clean[i];
  }
  r[12].symbol = static_cast<std::uint8_t>((clean[12] + 3) % 32);
  for (auto& s : r) {
    if (s.runner_up < 0) s.runner_up = (s.symbol + 1) % 32;
  }
  EXPECT_FALSE(decode_frame(r, 4, 0)) << "erasures alone";
  const auto chased = decode_frame(r, 4, 4);
  ASSERT_TRUE(chased);
  EXPECT_EQ(chased->frame, f);
  EXPECT_LE(chased->errors, 1) << "a swapped try keeps 3 parity symbols for detection: it corrects one error";

  r[14].symbol = static_cast<std::uint8_t>((clean[14] + 5) % 32);  // a second confident misread
  r[14].runner_up = (r[14].symbol + 1) % 32;
  EXPECT_FALSE(decode_frame(r, 4, 4)) << "two errors left after the swaps: one too many for a swapped try";
}

// Noise read as sixteen random tones: with two parity symbols kept and the CRC, not one of a
// 300 000 random words decodes (each would be a wrong accept), the runner-up swaps included.
TEST(FrameCode, RandomTonesNeverDecode) {
  std::mt19937 rng(9);
  int decoded = 0;
  for (int trial = 0; trial < 300000; ++trial) {
    std::array<SymbolReading, kCodeSymbols> r{};
    for (auto& s : r) {
      s = {static_cast<std::uint8_t>(rng() & 31), 1.0f + static_cast<float>(rng() % 100) / 10.0f, rng() % 8 != 0};
      s.runner_up = static_cast<int>(rng() & 31);
    }
    decoded += decode_frame(r, 4, 4) ? 1 : 0;
  }
  EXPECT_EQ(decoded, 0);
}

TEST(FrameGate, AcceptsAFrameOnceAndDropsItsNeighbours) {
  FrameGate gate(30, 25);
  const GateFrame f{2, command_frame_pack({0, 1, 42})};
  EXPECT_FALSE(gate.on_candidate(0, 100, false));  // a straddling window before it
  const auto v = gate.on_candidate(0, 110, true, f);
  ASSERT_TRUE(v);
  EXPECT_TRUE(v->accepted);
  EXPECT_EQ(v->frame.bits, f.bits);
  EXPECT_FALSE(gate.on_candidate(0, 120, true, f));  // the same frame a hop later
  EXPECT_FALSE(gate.on_candidate(0, 130, false));    // a straddling window after it
  EXPECT_FALSE(gate.on_time(200)) << "the failed window before the frame belonged to it";
  EXPECT_TRUE(gate.on_candidate(0, 215, true, f)) << "a retransmission a frame later passes again";
}

TEST(FrameGate, AClusterOfFailedCandidatesEndsInOneNack) {
  FrameGate gate(30, 25);
  EXPECT_FALSE(gate.on_candidate(50, 100, false));
  EXPECT_FALSE(gate.on_candidate(60, 110, false));
  EXPECT_FALSE(gate.on_time(120));
  const auto nack = gate.on_time(140);
  ASSERT_TRUE(nack);
  EXPECT_FALSE(nack->accepted);
  EXPECT_DOUBLE_EQ(nack->start_ms, 50);
  EXPECT_FALSE(gate.on_time(400)) << "one NACK per cluster";
}

TEST(SequenceFilter, ARetransmissionIsNotExecutedTwiceButANewCommandIs) {
  SequenceFilter filter;
  EXPECT_TRUE(filter.first_time({0, 4, 100}));
  EXPECT_FALSE(filter.first_time({0, 4, 100})) << "the same frame after a lost ACK";
  EXPECT_TRUE(filter.first_time({0, 5, 100})) << "the same command sent anew";
  EXPECT_TRUE(filter.first_time({0, 5, 101})) << "same number, different frame: a new sender";
  filter.reset();
  EXPECT_TRUE(filter.first_time({0, 5, 101}));
}

TEST(FrameGate, AFailedClusterWaitsToSettleAndAnAcceptClosesItSilently) {
  FrameGate gate(70, 25, 80);
  const GateFrame f{3, 1};
  // A room's tail paired with the next frame's first chord (or the first two chords of an
  // authenticated frame), then that frame's own chords.
  EXPECT_FALSE(gate.on_candidate(0, 100, false));
  EXPECT_FALSE(gate.on_time(130)) << "quiet for 30 ms, but not yet settled";
  EXPECT_TRUE(gate.on_candidate(50, 150, true, f));
  EXPECT_FALSE(gate.on_time(400)) << "the accept closed the cluster: no NACK";
  // A broken frame alone still gets its one NACK, once settled.
  EXPECT_FALSE(gate.on_candidate(1000, 1100, false));
  EXPECT_FALSE(gate.on_time(1150));
  const auto nack = gate.on_time(1180);
  ASSERT_TRUE(nack);
  EXPECT_FALSE(nack->accepted);
  EXPECT_FALSE(gate.on_time(1300));
}

// Every reply a robot can give: ACK 0..15 and NACK, from each of the 8 addresses.
std::vector<NamedReply> every_reply() {
  std::vector<NamedReply> all;
  for (std::uint8_t address = 0; address < 8; ++address) {
    for (std::uint8_t s = 0; s < 16; ++s) all.push_back({true, s, address});
    all.push_back({false, 0, address});
  }
  return all;
}

TEST(ReplyCode, NamedRepliesDifferInSevenOfTwelveTonesAndAreReadWithAnyThreeLost) {
  std::mt19937 rng(3);
  const auto all = every_reply();
  ASSERT_EQ(all.size(), 136u);
  for (const NamedReply& reply : all) {
    const ReplyTones word = reply_codeword(reply);
    for (const NamedReply& other : all) {
      if (other == reply) continue;
      const ReplyTones w2 = reply_codeword(other);
      int differ = 0;
      for (std::size_t t = 0; t < word.size(); ++t) differ += word[t] != w2[t];
      EXPECT_GE(differ, 7) << "address " << int(reply.address) << " and " << int(other.address);
    }
    ReplyReading reading{};
    for (std::size_t t = 0; t < word.size(); ++t) reading[t] = word[t];
    EXPECT_EQ(read_reply(reading, 9), reply);
    for (int trial = 0; trial < 20; ++trial) {
      auto damaged = reading;
      std::array<int, kReplyTones> order{};
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), rng);
      for (int k = 0; k < 3; ++k)  // lost, or read as another tone
        damaged[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] =
            k % 2 ? -1 : (word[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] + 1) % kReplyToneValues;
      EXPECT_EQ(read_reply(damaged, 9), reply) << "with three tones gone";
      damaged[static_cast<std::size_t>(order[3])] = -1;
      EXPECT_FALSE(read_reply(damaged, 9).has_value() && *read_reply(damaged, 9) != reply)
          << "four tones gone never name another reply";
    }
  }
}

// Address 0's replies are the single-robot code's words (found by its seeded search, the
// same on every machine), so robots and senders of that time still understand each other.
TEST(ReplyCode, AddressZeroKeepsTheSingleRobotWords) {
  std::mt19937 rng(20261125);
  std::vector<ReplyTones> kept;
  while (kept.size() < 17) {
    ReplyTones w{};
    for (auto& t : w) t = static_cast<std::uint8_t>(rng() % kReplyToneValues);
    bool far = true;
    for (std::size_t b = 0; b < 6; ++b) far = far && w[b] != w[b + 6];
    for (const auto& k : kept) {
      int differ = 0;
      for (std::size_t t = 0; t < w.size(); ++t) differ += w[t] != k[t];
      far = far && differ >= 7;
    }
    if (far) kept.push_back(w);
  }
  for (std::uint8_t s = 0; s < 16; ++s) EXPECT_EQ(reply_codeword({true, s, 0}), kept[s]) << "ACK " << int(s);
  EXPECT_EQ(reply_codeword({false, 0, 0}), kept[16]) << "NACK";
}

// No reply repeats a band's tone from its first chord in its second.
TEST(ReplyCode, NoReplyRepeatsABandsToneInItsSecondChord) {
  for (const NamedReply& reply : every_reply()) {
    const ReplyTones word = reply_codeword(reply);
    for (std::size_t b = 0; b < 6; ++b) EXPECT_NE(word[b], word[b + 6]) << "address " << int(reply.address);
  }
}
