// A frame read again out of the room's echo of it (reliability/echo_memory.h): the end of a
// run of the end-to-end test, as the sender's loudspeaker played it (recorded from the test
// air: data/seminar_run_end_loudspeaker.flac, the last 19 frames of a sequence and 2 s of the
// quiet after them), through the seminar room's measured response at 1 m as the test air's
// bridge passes it. In that quiet the robot read the last two frames again 0.7-0.9 s after it
// had taken them, and executed the older one (a full-speed turn) a second time, after the
// stop that had followed it.
#include <gtest/gtest.h>

#include <map>
#include <memory>

#include "link/link.h"
#include "physical/wav_file.h"
#include "reliability/echo_memory.h"
#include "sim/acoustic_channel.h"
#include "sim/room_model.h"

using namespace dtmf;

namespace {

const LinkProfile& p = fast_profile();

struct Heard {
  std::map<std::uint8_t, int> executed;  // per sequence number
  int repeats = 0;
  int frames = 0;
  int failed = 0;
  std::size_t echoes_ignored = 0;
};

Heard hear(const std::vector<float>& audio) {
  const auto link = link::make_link(p);
  const auto receiver = link->receiver();
  Heard h;
  for (std::size_t at = 0; at < audio.size(); at += 1024) {
    const auto n = std::min<std::size_t>(1024, audio.size() - at);
    for (const auto& r : receiver->feed(std::span<const float>(audio.data() + at, n))) {
      ++h.frames;
      h.failed += r.intact ? 0 : 1;
      if (r.event == link::ReceptionEvent::Command) ++h.executed[*r.sequence];
      if (r.event == link::ReceptionEvent::Repeat) ++h.repeats;
    }
  }
  h.echoes_ignored = receiver->echoes_ignored();
  return h;
}

std::vector<float> through_seminar_room(const std::vector<float>& played) {
  sim::ChannelConfig room;
  room.room.rir_file = std::string(DTMF_RIR_DIR) + "/seminar_room_clap.wav";
  const auto model = std::make_shared<const sim::RoomModel>(room.room, p.sample_rate_hz);
  sim::AcousticChannel channel(p.sample_rate_hz, room, model);
  channel.add_transmitter(1.0);
  std::vector<float> heard;
  channel.process(played, heard);
  return heard;
}

}  // namespace

TEST(RoomEcho, AFrameReadAgainFromTheRoomsTailIsNeitherExecutedNorAnswered) {
  const auto played = physical::read_audio_file(DTMF_LINK_TEST_DATA "/seminar_run_end_loudspeaker.flac", 48000);
  ASSERT_GT(played.size(), 6u * 48000);
  // What the loudspeaker played, heard with no room between: each frame once.
  const Heard played_frames = hear(played);
  ASSERT_EQ(played_frames.frames, 19);
  ASSERT_EQ(played_frames.repeats, 0);
  const Heard h = hear(through_seminar_room(played));
  EXPECT_EQ(h.failed, 0);
  EXPECT_EQ(h.executed, played_frames.executed) << "each frame executed once, as played";
  EXPECT_EQ(h.echoes_ignored, 1u) << "the turn's echo, 0.94 s after it";
  EXPECT_EQ(h.repeats, 1) << "the closing stop's echo: to the robot, a retransmission";
  EXPECT_EQ(h.frames, 20);
}

TEST(EchoMemory, TheNewestIsNoEchoAnOlderOneWithinTheHorizonIs) {
  using reliability::FrameBits;
  reliability::EchoMemory m(1000);
  const FrameBits a(0x1234), b(0x5678);
  EXPECT_FALSE(m.is_echo(a, 0)) << "nothing taken yet";
  m.remember(a, 0);
  EXPECT_FALSE(m.is_echo(a, 300)) << "the newest: a retransmission, or its echo, answered";
  m.remember(b, 250);
  EXPECT_TRUE(m.is_echo(a, 900));
  EXPECT_FALSE(m.is_echo(b, 900));
  EXPECT_FALSE(m.is_echo(a, 1001)) << "past the horizon: the sequence number may have come round";
  EXPECT_FALSE(m.is_echo(FrameBits(0x9999), 500)) << "never taken";
}

TEST(EchoMemory, RemembersTheLastFifteenFramesOnly) {
  using reliability::FrameBits;
  reliability::EchoMemory m(1e9);
  for (int i = 0; i < 16; ++i) m.remember(FrameBits(100 + i), i);
  EXPECT_FALSE(m.is_echo(FrameBits(100), 20)) << "sixteen frames ago: its number may be new again";
  EXPECT_TRUE(m.is_echo(FrameBits(101), 20));
  EXPECT_TRUE(m.is_echo(FrameBits(114), 20));
  EXPECT_FALSE(m.is_echo(FrameBits(115), 20)) << "the newest";
}
