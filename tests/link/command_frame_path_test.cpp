// The fast profile through every layer (ggwave-style): every command kind with every
// sequence number over the simulated room, a retransmission answered but not re-executed,
// frames at -10 dB SNR, and sounds that are no frames.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "command/command_payload.h"
#include "command/test_sequence.h"
#include "link/sender_path.h"
#include "link/command_frame_path.h"
#include "physical/acoustic_channel.h"

using namespace dtmf;

namespace {
const LinkProfile& p = fast_profile();

std::string quantised_text(const command::Command& c) {
  return command::describe(*command::decode_payload(command::encode_payload(c)).command);
}

std::vector<link::ReceivedCommandFrame> receive(const std::vector<float>& audio) {
  link::CommandFramePath path(p);
  std::vector<link::ReceivedCommandFrame> got;
  for (std::size_t at = 0; at < audio.size(); at += 1024) {
    const auto n = std::min<std::size_t>(1024, audio.size() - at);
    for (const auto& r : path.feed(std::span<const float>(audio.data() + at, n))) got.push_back(r);
  }
  return got;
}

const std::vector<command::Command> kEveryKind = {
    command::Reset{}, command::Stop{}, command::DriveForDuration{50, 2}, command::TurnForDuration{-25, 1.5},
    command::DriveForward{80}, command::Turn{33.3}};
}  // namespace

class CommandFramePathRoom : public ::testing::TestWithParam<double> {};

// Frames 100 ms apart (the next follows an ACK) in a quiet room's pink noise, at 1 m and at
// 5 m, where the tail of one frame, paired with the next frame's first chord, looks like a
// frame a chord before that frame's own pair.
TEST_P(CommandFramePathRoom, EveryKindWithEverySequenceNumberComesBackOnceWithNoNack) {
  physical::ChannelConfig room;
  room.noise = physical::parse_noise("pink", -45);
  room.reverb.rt60_s = 0.3;
  physical::AcousticChannel channel(p.sample_rate_hz, room);
  channel.add_transmitter(GetParam());
  std::vector<float> sent, heard;
  std::vector<std::string> expected;
  for (int seq = 0; seq < 16; ++seq) {
    for (const auto& c : kEveryKind) {
      // About one frame in 16 takes a later number, so that its chords share no tone.
      const auto planned = link::plan_command_frame(c, static_cast<std::uint8_t>(seq));
      const auto f = link::render_command_frame(p, planned);
      sent.insert(sent.end(), f.begin(), f.end());
      sent.insert(sent.end(), 4800, 0.0f);  // 100 ms, as if waiting for the ACK
      expected.push_back(std::to_string(planned.frame.sequence) + " " + quantised_text(c));
    }
  }
  sent.insert(sent.end(), 9600, 0.0f);
  channel.process(sent, heard);
  std::vector<std::string> got;
  for (const auto& r : receive(heard)) {
    ASSERT_TRUE(r.frame) << "a NACK at " << r.start_ms << " ms " << r.error << " after " << got.size();
    ASSERT_TRUE(r.command) << "repeat at " << r.start_ms << " after " << got.size();
    got.push_back(std::to_string(r.frame->sequence) + " " + command::describe(*r.command));
  }
  EXPECT_EQ(got, expected);
}

INSTANTIATE_TEST_SUITE_P(Distances, CommandFramePathRoom, ::testing::Values(1.0, 5.0));

TEST(CommandFramePath, ARetransmittedFrameIsAnsweredButNotExecutedAgain) {
  const auto frame = link::render_command_frame(p, link::plan_command_frame(command::DriveForward{40}, 7));
  std::vector<float> audio(2000, 0.0f);
  for (int i = 0; i < 2; ++i) {
    audio.insert(audio.end(), frame.begin(), frame.end());
    audio.insert(audio.end(), 20000, 0.0f);  // the ACK was lost; the sender waits, then repeats
  }
  const auto got = receive(audio);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_TRUE(got[0].command);
  EXPECT_FALSE(got[0].repeat);
  ASSERT_TRUE(got[1].frame);
  EXPECT_EQ(got[1].frame->sequence, 7);
  EXPECT_TRUE(got[1].repeat);
  EXPECT_FALSE(got[1].command);
}

TEST(CommandFramePath, AtMinusTenDbSnrFramesBackToBackAreHeardWithNoWrongAccept) {
  constexpr int kFrames = 1000;
  std::mt19937 rng(11);
  std::vector<float> audio;
  std::vector<std::uint64_t> bits;
  for (int i = 0; i < kFrames; ++i) {
    const command::Command c = command::DriveForDuration{static_cast<double>(rng() % 1001) / 10.0,
                                                        static_cast<double>(rng() % 801) / 100.0};
    const auto planned = link::plan_command_frame(c, static_cast<std::uint8_t>(i));
    bits.push_back(planned.bits);
    const auto f = link::render_command_frame(p, planned);
    audio.insert(audio.end(), f.begin(), f.end());
  }
  double power = 0;
  for (const float s : audio) power += static_cast<double>(s) * s;
  power /= static_cast<double>(audio.size());
  audio.insert(audio.begin(), 5000, 0.0f);
  audio.insert(audio.end(), 5000, 0.0f);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(std::sqrt(power * 10.0)));  // -10 dB
  for (float& s : audio) s += noise(rng);

  const double frame_ms = 1000.0 * p.bins.frame_samples() / p.sample_rate_hz;
  std::vector<int> accepted(kFrames, 0);
  int wrong = 0;
  for (const auto& r : receive(audio)) {
    if (!r.frame) continue;
    const auto slot = static_cast<long>(std::lround((r.start_ms - 5000.0 / 48.0) / frame_ms));
    if (slot < 0 || slot >= kFrames || bits[static_cast<std::size_t>(slot)] != r.bits) {
      ++wrong;
    } else {
      ++accepted[static_cast<std::size_t>(slot)];
    }
  }
  const long once = std::count(accepted.begin(), accepted.end(), 1);
  std::printf("-10 dB SNR: %ld of %d frames accepted exactly once, %d wrong accepts\n", once, kFrames, wrong);
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(once, kFrames * 99 / 100);
}

TEST(CommandFramePath, AHeldChordOrSilenceExecutesNothing) {
  auto frame = link::render_command_frame(p, link::plan_command_frame(command::Turn{50}, 3));
  // The first chord held for a second: the same symbols in both chords' windows.
  const auto chord = static_cast<std::size_t>(p.bins.chord_samples());
  std::vector<float> held(2000, 0.0f);
  for (int i = 0; i < 19; ++i) held.insert(held.end(), frame.begin(), frame.begin() + static_cast<long>(chord));
  held.insert(held.end(), 5000, 0.0f);
  for (const auto& r : receive(held)) EXPECT_FALSE(r.command);
  EXPECT_TRUE(receive(std::vector<float>(96000, 0.0f)).empty());
}

// The agent listens with both profiles: the seed's chords must leave the fast path silent,
// not even a NACK (which would put a reply on the air and a row in the report).
TEST(CommandFramePath, TheSeedsChordsMakeNoVerdictAtAll) {
  const LinkProfile& seed = seed_profile();
  std::vector<link::PlannedFrame> frames;
  for (const auto& c : command::seed_test_sequence()) {
    for (const auto& f : link::plan_command(seed, c)) frames.push_back(f);
  }
  physical::ChannelConfig room;
  room.noise = physical::parse_noise("white", -70);
  room.reverb.rt60_s = 0.3;
  physical::AcousticChannel channel(p.sample_rate_hz, room);
  channel.add_transmitter(1.0);
  std::vector<float> heard;
  channel.process(link::render_frames(seed, frames), heard);
  const auto got = receive(heard);
  int nacks = 0;
  for (const auto& r : got) nacks += !r.frame;
  EXPECT_EQ(got.size(), 0u) << nacks << " NACKs for " << frames.size() << " seed chords";
}
