// Signal layer: the listeners put together, on clean synthesized audio.
#include <gtest/gtest.h>

#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
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
  EXPECT_NEAR(heard[0].start_ms, 1234, 1000.0 / p.analysis.analyses_per_s);
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
