// The robot's whole receive path on the seed's 65-frame test sequence, near and far.
#include <gtest/gtest.h>

#include "command/test_sequence.h"
#include "command/word_codec.h"
#include "link/seed_sender_path.h"
#include "profile/link_profile.h"
#include "support/listen.h"
#include "support/seed_audio.h"

using namespace dtmf;

namespace {

std::vector<link::SeedPlannedFrame> sequence_frames(const LinkProfile& p) {
  std::vector<link::SeedPlannedFrame> frames;
  for (const auto& command : command::seed_test_sequence()) {
    for (const auto& f : link::plan_command(p, command)) frames.push_back(f);
  }
  return frames;
}

}  // namespace

TEST(TestSequence, Has65FramesAsTheSeedCounts) {
  EXPECT_EQ(command::frame_count(command::seed_test_sequence()), 65u);
  EXPECT_EQ(command::seed_test_sequence().size(), 5u + 5 + 5 + 6 + 6);
}

class SequenceAtDistance : public ::testing::TestWithParam<double> {};

TEST_P(SequenceAtDistance, AllFramesHeardOnceInOrderAndEveryCommandExecuted) {
  const LinkProfile& p = seed_profile();
  const auto frames = sequence_frames(p);
  sim::ChannelConfig room;
  room.noise = sim::parse_noise("pink", -60);
  room.reverb.rt60_s = 0.3;
  room.reverb.wet = 0.2;
  room.clock_offset_ppm = 50;
  const auto heard_audio =
      test_support::through_channel(test_support::seed_audio(p, frames), p.sample_rate_hz, GetParam(), room);
  const auto received = test_support::receive(p, heard_audio);

  ASSERT_EQ(received.size(), frames.size());
  std::vector<std::string> executed;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(received[i].frame, frames[i].frame) << i;
    EXPECT_TRUE(received[i].crc_ok) << i;
    EXPECT_NEAR(received[i].start_ms, link::frame_start_ms(p, i) + GetParam() / 0.343, 60) << i;
    if (received[i].event && received[i].event->command)
      executed.push_back(command::describe(*received[i].event->command));
  }
  std::vector<std::string> expected;
  for (const auto& c : command::seed_test_sequence()) {
    if (!std::holds_alternative<command::Reset>(c)) expected.push_back(command::describe(command::quantised(c)));
  }
  EXPECT_EQ(executed, expected);
}

INSTANTIATE_TEST_SUITE_P(Metres, SequenceAtDistance, ::testing::Values(1.0, 4.0, 7.0, 10.0));

TEST(SeedReceiverPath, ACorruptedChordIsHeardButFailsTheCrcAndChangesNothing) {
  const LinkProfile& p = seed_profile();
  std::vector<link::SeedPlannedFrame> frames = {
      link::plan_word(p, command::kResetWord),
      link::plan_word(p, static_cast<command::Word>(command::Mode::DriveForward))};
  // One tone moved: bits 0..3 (the CRC band) changed, so the CRC no longer matches.
  link::SeedPlannedFrame bad = link::plan_word(p, 0x800);
  bad.frame ^= 0x0003;
  bad.tones_hz = signal::chord_for(p.words().tones, bad.frame);
  frames.push_back(bad);
  const auto received = test_support::receive(p, test_support::seed_audio(p, frames));
  ASSERT_EQ(received.size(), 3u);
  EXPECT_TRUE(received[1].crc_ok);
  EXPECT_FALSE(received[2].crc_ok);
  EXPECT_FALSE(received[2].event);
  EXPECT_EQ(received[2].frame, bad.frame);
}
