// The fast profile's reliability layer: the 48-bit frame, the chase decoder, the frame
// gate (one verdict per frame) and the sequence filter (no double execution).
#include <gtest/gtest.h>

#include <random>

#include "reliability/chase_decoder.h"
#include "reliability/command_frame.h"
#include "reliability/frame_gate.h"
#include "reliability/sequence_filter.h"

using namespace dtmf::reliability;

TEST(Crc16, MatchesCcittFalseReferenceValues) {
  // binascii.crc_hqx(data, 0xFFFF) in Python computes CRC-16/CCITT-FALSE.
  EXPECT_EQ(crc16(0x12345678, 32), 0x30EC);
  EXPECT_EQ(crc16(0x3132333435363738ull, 64), 0xA12B);  // "12345678"
}

TEST(CommandFrame, PacksSequencePayloadAndCrcAndUnpacksThem) {
  const CommandFrame f{11, 0x2ABCDEF};
  const std::uint64_t bits = pack(f);
  EXPECT_EQ(bits >> 44, 11u);
  EXPECT_EQ((bits >> 16) & kPayloadMask, 0x2ABCDEFu);
  EXPECT_EQ(bits & 0xFFFF, crc16(bits >> 16, 32));
  EXPECT_EQ(unpack(bits), f);
  EXPECT_EQ(from_symbols(to_symbols(bits)), bits);
  EXPECT_FALSE(unpack(0).has_value()) << "the all-zero frame is not a codeword";
}

TEST(CommandFrame, EveryWrongSymbolAndEveryPairOfWrongBitsIsCaught) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const CommandFrame f{static_cast<std::uint8_t>(rng() & 15), static_cast<std::uint32_t>(rng()) & kPayloadMask};
    const Symbols good = to_symbols(pack(f));
    for (std::size_t s = 0; s < kCommandSymbols; ++s) {
      for (int v = 0; v < 64; ++v) {
        if (v == good[s]) continue;
        Symbols bad = good;
        bad[s] = static_cast<std::uint8_t>(v);
        ASSERT_FALSE(unpack(from_symbols(bad))) << "symbol " << s << " -> " << v;
      }
    }
    const std::uint64_t bits = pack(f);
    for (int i = 0; i < 48; ++i) {
      for (int j = i + 1; j < 48; ++j) ASSERT_FALSE(unpack(bits ^ (1ull << i) ^ (1ull << j)));
    }
  }
}

namespace {
SymbolReading reading_of(const CommandFrame& f) {
  SymbolReading r;
  r.symbols = to_symbols(pack(f));
  r.runner_up = r.symbols;
  for (auto& u : r.runner_up) u = static_cast<std::uint8_t>((u + 1) % 64);
  r.certainty.fill(10.0f);
  return r;
}
}  // namespace

TEST(ChaseDecoder, TakesTheFrameAsHeardWhenItsCrcHolds) {
  const CommandFrame f{3, 0x1234567};
  const auto got = chase_decode(reading_of(f), 2);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->frame, f);
  EXPECT_EQ(got->substitutions, 0);
}

TEST(ChaseDecoder, RepairsTheLeastCertainSymbolWithItsRunnerUpOnly) {
  const CommandFrame f{9, 0x0ABCDEF};
  SymbolReading r = reading_of(f);
  const auto truth = r.symbols[5];
  r.symbols[5] = 17 == truth ? 18 : 17;  // heard wrong ...
  r.runner_up[5] = truth;                // ... with the truth close behind
  r.certainty[5] = 1.1f;
  r.certainty[2] = 1.5f;
  const auto got = chase_decode(r, 2);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->frame, f);
  EXPECT_EQ(got->substitutions, 1);

  r.certainty[5] = 20.0f;  // no longer among the two least certain: not tried
  EXPECT_FALSE(chase_decode(r, 2));
  r.certainty[5] = 1.1f;
  EXPECT_FALSE(chase_decode(r, 0)) << "no chase asked for";
  r.symbols[0] = static_cast<std::uint8_t>((r.symbols[0] + 5) % 64);  // a second wrong symbol
  EXPECT_FALSE(chase_decode(r, 2));
}

TEST(FrameGate, AcceptsAFrameOnceAndDropsItsNeighbours) {
  FrameGate gate(30, 25);
  const ChasedFrame f{{1, 42}, pack({1, 42}), 0};
  EXPECT_FALSE(gate.on_candidate(0, 100, std::nullopt));  // a straddling window before it
  const auto v = gate.on_candidate(0, 110, f);
  ASSERT_TRUE(v);
  EXPECT_TRUE(v->accepted);
  EXPECT_FALSE(gate.on_candidate(0, 120, f));             // the same frame a hop later
  EXPECT_FALSE(gate.on_candidate(0, 130, std::nullopt));  // a straddling window after it
  EXPECT_FALSE(gate.on_time(200)) << "the failed window before the frame belonged to it";
  EXPECT_TRUE(gate.on_candidate(0, 215, f)) << "a retransmission a frame later passes again";
}

TEST(FrameGate, AClusterOfFailedCandidatesEndsInOneNack) {
  FrameGate gate(30, 25);
  EXPECT_FALSE(gate.on_candidate(50, 100, std::nullopt));
  EXPECT_FALSE(gate.on_candidate(60, 110, std::nullopt));
  EXPECT_FALSE(gate.on_time(120));
  const auto nack = gate.on_time(140);
  ASSERT_TRUE(nack);
  EXPECT_FALSE(nack->accepted);
  EXPECT_DOUBLE_EQ(nack->start_ms, 50);
  EXPECT_FALSE(gate.on_time(400)) << "one NACK per cluster";
}

TEST(SequenceFilter, ARetransmissionIsNotExecutedTwiceButANewCommandIs) {
  SequenceFilter filter;
  EXPECT_TRUE(filter.first_time({4, 100}));
  EXPECT_FALSE(filter.first_time({4, 100})) << "the same frame after a lost ACK";
  EXPECT_TRUE(filter.first_time({5, 100})) << "the same command sent anew";
  EXPECT_TRUE(filter.first_time({5, 101})) << "same number, different frame: a new sender";
  filter.reset();
  EXPECT_TRUE(filter.first_time({5, 101}));
}

TEST(FrameGate, AFailedClusterWaitsToSettleAndAnAcceptClosesItSilently) {
  FrameGate gate(70, 25, 80);
  ChasedFrame f;
  f.bits = 1;
  // A room's tail paired with the next frame's first chord, then that frame's own pair.
  EXPECT_FALSE(gate.on_candidate(0, 100, std::nullopt));
  EXPECT_FALSE(gate.on_time(130)) << "quiet for 30 ms, but not yet settled";
  EXPECT_TRUE(gate.on_candidate(50, 150, f));
  EXPECT_FALSE(gate.on_time(400)) << "the accept closed the cluster: no NACK";
  // A broken frame alone still gets its one NACK, once settled.
  EXPECT_FALSE(gate.on_candidate(1000, 1100, std::nullopt));
  EXPECT_FALSE(gate.on_time(1150));
  const auto nack = gate.on_time(1180);
  ASSERT_TRUE(nack);
  EXPECT_FALSE(nack->accepted);
  EXPECT_FALSE(gate.on_time(1300));
}
