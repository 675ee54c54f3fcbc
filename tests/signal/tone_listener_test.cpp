// Signal layer: the listeners put together, on clean synthesized audio.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
#include "sim/fft_convolver.h"
#include "sim/measured_rir.h"
#include "support/listen.h"

using namespace dtmf;
using namespace dtmf::signal;

namespace {
std::vector<float> with_silence(std::vector<float> sound, int before, int after) {
  std::vector<float> out(static_cast<std::size_t>(before), 0.0f);
  out.insert(out.end(), sound.begin(), sound.end());
  out.resize(out.size() + static_cast<std::size_t>(after), 0.0f);
  return out;
}
}  // namespace

TEST(ChordListener, HearsOneChordOnceWithItsStartTime) {
  const LinkProfile& p = seed_profile();
  const int before = p.samples_for_ms(1234);
  const auto audio = with_silence(synthesize_frame(p, 0xB2DD), before, p.samples_for_ms(1000));
  auto listener = chord_listener(p);
  const auto heard = test_support::listen(listener, audio);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].symbol, 0xB2DDu);
  EXPECT_NEAR(heard[0].start_ms, 1234, 1000.0 / p.words().analysis.analyses_per_s);
  // Two detections at 20 per second: heard within about 0.15 s of the start.
  EXPECT_GT(heard[0].heard_ms, 1234);
  EXPECT_LT(heard[0].heard_ms, 1234 + 200);
}

TEST(ChordListener, BlockSizeDoesNotChangeWhatIsHeard) {
  const LinkProfile& p = seed_profile();
  const auto audio = with_silence(synthesize_frame(p, 0x0F0F), 1000, 20000);
  for (std::size_t block : {1ul, 100ul, 2400ul, 4096ul, audio.size()}) {
    auto listener = chord_listener(p);
    const auto heard = test_support::listen(listener, audio, block);
    ASSERT_EQ(heard.size(), 1u) << block;
    EXPECT_EQ(heard[0].symbol, 0x0F0Fu);
  }
}

TEST(ChordListener, AChordAtTheVeryStartIsHeard) {
  const LinkProfile& p = seed_profile();
  auto listener = chord_listener(p);
  const auto heard = test_support::listen(listener, with_silence(synthesize_frame(p, 0x1111), 0, 1000));
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_LT(heard[0].start_ms, 50);
}

TEST(ReplyListener, HearsAckAndNackButNotCommandChords) {
  const LinkProfile& p = seed_profile();
  std::vector<float> audio = with_silence(synthesize_reply(p, Reply::Ack), 4800, 24000);
  const auto nack = synthesize_reply(p, Reply::Nack);
  audio.insert(audio.end(), nack.begin(), nack.end());
  const auto command = synthesize_frame(p, 0x0000);
  audio.insert(audio.end(), command.begin(), command.end());
  audio.resize(audio.size() + 24000, 0.0f);
  auto listener = reply_listener(p);
  const auto heard = test_support::listen(listener, audio);
  ASSERT_EQ(heard.size(), 2u);
  EXPECT_EQ(static_cast<Reply>(heard[0].symbol), Reply::Ack);
  EXPECT_EQ(static_cast<Reply>(heard[1].symbol), Reply::Nack);
}

TEST(ChordListener, DoesNotHearReplies) {
  const LinkProfile& p = seed_profile();
  auto listener = chord_listener(p);
  EXPECT_TRUE(test_support::listen(listener, with_silence(synthesize_reply(p, Reply::Ack), 1000, 1000)).empty());
}

// A sender kept off the CPU plays its chord with a hole in it (seen on a CI machine: up to
// 460 ms). The robot must hear the chord once, clean and through a measured room, while the
// same chord sent again after the seed's 0.2 s gap is heard twice.
namespace {

std::vector<float> chord_with_a_hole(const LinkProfile& p, std::uint16_t frame, double hole_at_ms, double hole_ms) {
  const auto chord = synthesize_frame(p, frame);
  const auto at = static_cast<std::ptrdiff_t>(p.samples_for_ms(hole_at_ms));
  std::vector<float> audio(chord.begin(), chord.begin() + at);
  audio.resize(audio.size() + static_cast<std::size_t>(p.samples_for_ms(hole_ms)), 0.0f);
  audio.insert(audio.end(), chord.begin() + at, chord.end());
  return with_silence(audio, p.samples_for_ms(500), p.samples_for_ms(2000));
}

std::vector<float> through_the_seminar_room(const LinkProfile& p, const std::vector<float>& audio) {
  const auto rir = sim::load_measured_rir(DTMF_RIR_DIR "/seminar_room_clap.wav", p.sample_rate_hz);
  sim::FftConvolver room(rir.samples);
  std::vector<float> heard(audio.size(), 0.0f);
  room.process_add(audio, heard);
  return heard;
}

std::size_t times_heard(const LinkProfile& p, const std::vector<float>& audio, std::uint16_t frame) {
  auto listener = chord_listener(p);
  std::size_t count = 0;
  for (const Heard& h : test_support::listen(listener, audio)) {
    EXPECT_EQ(h.symbol, frame);
    count += h.symbol == frame;
  }
  return count;
}

}  // namespace

TEST(ChordListener, AChordWithAHoleInItIsHeardOnce) {
  const LinkProfile& p = seed_profile();
  for (const double hole_ms : {90.0, 250.0, 460.0}) {
    for (const double hole_at_ms : {200.0, 500.0}) {
      const auto audio = chord_with_a_hole(p, 0xB2DD, hole_at_ms, hole_ms);
      EXPECT_EQ(times_heard(p, audio, 0xB2DD), 1u) << hole_ms << " ms after " << hole_at_ms << " ms, clean";
      EXPECT_EQ(times_heard(p, through_the_seminar_room(p, audio), 0xB2DD), 1u)
          << hole_ms << " ms after " << hole_at_ms << " ms, seminar room";
    }
  }
}

TEST(ChordListener, TheSameChordSentAgainAfterTheGapIsHeardTwice) {
  const LinkProfile& p = seed_profile();
  auto audio = with_silence(synthesize_frame(p, 0xB2DD), p.samples_for_ms(500), p.samples_for_ms(p.timing.gap_ms));
  const auto again = with_silence(synthesize_frame(p, 0xB2DD), 0, p.samples_for_ms(2000));
  audio.insert(audio.end(), again.begin(), again.end());
  EXPECT_EQ(times_heard(p, audio, 0xB2DD), 2u);
  EXPECT_EQ(times_heard(p, through_the_seminar_room(p, audio), 0xB2DD), 2u);
}

// A fan whining 6 dB over a plan tone, on that tone's very frequency (5000 Hz: band 0, value
// 3), for 8 s before a chord that uses the tone. Whatever the whine's phase against the
// tone's, the chord is heard once and right: the listener takes the whine off phase and all
// (signal/steady_phasors.h). With its power alone taken off, the tone's excess would be
// anything from nothing to more than twice its power as the two phases turn.
TEST(ChordListener, AChordIsHeardThroughAWhineOnItsOwnToneAtEveryPhase) {
  const LinkProfile& p = seed_profile();
  constexpr std::uint16_t kFrame = 0x3A5C;
  const auto chord = synthesize_frame(p, kFrame);
  for (int k = 0; k < 12; ++k) {
    auto audio = with_silence(chord, p.samples_for_ms(8000), p.samples_for_ms(1000));
    const double phase = 2 * std::numbers::pi * k / 12;
    for (std::size_t i = 0; i < audio.size(); ++i) {
      audio[i] += static_cast<float>(
          2 * p.words().tones.tone_amplitude *
          std::sin(2 * std::numbers::pi * 5000.0 * static_cast<double>(i) / p.sample_rate_hz + phase));
    }
    auto listener = chord_listener(p);
    const auto heard = test_support::listen(listener, audio);
    ASSERT_EQ(heard.size(), 1u) << "whine phase " << phase;
    EXPECT_EQ(heard[0].symbol, kFrame) << "whine phase " << phase;
  }
}
