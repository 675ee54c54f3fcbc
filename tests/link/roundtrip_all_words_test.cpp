// Every 12-bit word, through every layer and the simulated air, comes back exactly once.
//
// word -> CRC frame -> chord -> audio -> channel (1 m, quiet room) -> spectrum -> chord
// -> debouncer -> CRC check. 4096 words of 1 s each: sharded so ctest can run the shards
// on both cores.
#include <gtest/gtest.h>

#include "link/seed_sender_path.h"
#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;

namespace {
constexpr int kShards = 4;
constexpr int kWordsPerShard = 4096 / kShards;
}  // namespace

class AllWords : public ::testing::TestWithParam<int> {};

TEST_P(AllWords, EveryWordIsRecoveredOnceAndNothingElseIsHeard) {
  const LinkProfile& p = seed_profile();
  sim::ChannelConfig quiet;
  quiet.noise = sim::parse_noise("white", -80);
  quiet.seed = static_cast<std::uint64_t>(GetParam()) + 1;
  sim::AcousticChannel channel(p.sample_rate_hz, quiet);
  channel.add_transmitter(1.0);
  auto listener = signal::chord_listener(p);

  const auto slot = static_cast<std::size_t>(p.samples_for_ms(p.timing.chord_ms + p.timing.gap_ms));
  const auto chord = static_cast<std::size_t>(p.samples_for_ms(p.timing.chord_ms));
  std::vector<float> block(slot), heard_audio;
  std::vector<reliability::SeedFrame> expected, heard;
  bool all_intact = true;
  auto listen = [&](std::span<const float> audio) {
    heard_audio.clear();
    channel.process(audio, heard_audio);
    for (const signal::Heard& h : listener.feed(heard_audio)) {
      heard.push_back(static_cast<reliability::SeedFrame>(h.symbol));
      all_intact = all_intact && reliability::word_frame_intact(static_cast<reliability::SeedFrame>(h.symbol));
    }
  };
  const int first = GetParam() * kWordsPerShard;
  for (int word = first; word < first + kWordsPerShard; ++word) {
    const link::SeedPlannedFrame frame = link::plan_word(p, static_cast<command::Word>(word));
    expected.push_back(frame.frame);
    std::fill(block.begin(), block.end(), 0.0f);
    signal::add_chord(std::span(block).first(chord), frame.tones_hz, p.words().tones.tone_amplitude,
                      p.words().tones.edge_ms, p.sample_rate_hz);
    listen(block);
  }
  listen(std::vector<float>(slot, 0.0f));  // let the last chord through the room

  EXPECT_TRUE(all_intact);
  ASSERT_EQ(heard.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(heard[i], expected[i]) << "word " << first + static_cast<int>(i);
  }
}

INSTANTIATE_TEST_SUITE_P(Shards, AllWords, ::testing::Range(0, kShards));
