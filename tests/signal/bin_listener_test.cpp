// The fast profile's signal layer: bin-centred chords in, the same symbols out, at every
// alignment of the analysis grid; replies named by sequence number; noise and lingering
// tones give nothing.
#include <gtest/gtest.h>

#include <random>

#include "profile/link_profile.h"
#include "signal/bin_frame_listener.h"
#include "signal/bin_reply_listener.h"
#include "signal/bin_synthesizer.h"
#include "signal/synthesizer.h"

using namespace dtmf;
using namespace dtmf::signal;

namespace {
std::vector<float> silence(std::size_t n) { return std::vector<float>(n, 0.0f); }

void append(std::vector<float>& to, const std::vector<float>& what) { to.insert(to.end(), what.begin(), what.end()); }

std::vector<FrameCandidate> listen(const LinkProfile& p, const std::vector<float>& audio) {
  BinFrameListener listener(p);
  std::vector<FrameCandidate> found;
  for (std::size_t at = 0; at < audio.size(); at += 1000) {
    const auto n = std::min<std::size_t>(1000, audio.size() - at);
    for (const auto& c : listener.feed(std::span<const float>(audio.data() + at, n))) found.push_back(c);
  }
  return found;
}
}  // namespace

TEST(BinFrameListener, EveryToneOfEveryBandIsReadBackAtAnyAlignment) {
  const LinkProfile& p = fast_profile();
  for (int v = 0; v < 64; ++v) {
    std::array<std::uint8_t, kFrameBands> symbols{};
    // The second chord never repeats a band's tone (senders never do: the listener refuses it).
    for (std::size_t i = 0; i < kFrameBands; ++i) {
      symbols[i] = static_cast<std::uint8_t>(i < 4 ? v : (v + 7 + 9 * static_cast<int>(i - 4)) % 64);
    }
    const std::size_t offset = static_cast<std::size_t>(v * 37 % p.bins.hop_samples);
    std::vector<float> audio = silence(2000 + offset);
    append(audio, synthesize_symbols(p, symbols));
    append(audio, silence(4000));
    const auto found = listen(p, audio);
    ASSERT_FALSE(found.empty()) << "value " << v;
    // Windows a hop or so either side of the inner one read the frame too; the inner one
    // dates it within half a hop.
    const double start_ms = (2000.0 + offset) / 48.0, half_hop_ms = 500.0 * p.bins.hop_samples / p.sample_rate_hz;
    bool exact = false;
    for (const auto& c : found) {
      EXPECT_EQ(c.symbols, symbols) << "value " << v;
      exact = exact || (c.absent == 0 && std::abs(c.start_ms - start_ms) <= half_hop_ms + 0.01);
    }
    EXPECT_TRUE(exact) << "value " << v << ", offset " << offset;
  }
}

TEST(BinFrameListener, NoiseAloneGivesNoCandidate) {
  const LinkProfile& p = fast_profile();
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  std::vector<float> audio(static_cast<std::size_t>(p.sample_rate_hz) * 20);
  for (float& s : audio) s = noise(rng);
  EXPECT_TRUE(listen(p, audio).empty());
  EXPECT_TRUE(listen(p, silence(48000)).empty());
}

TEST(BinFrameListener, AChordStillSoundingInTheNextIsNoFrameButAFadingTailIs) {
  const LinkProfile& p = fast_profile();
  const std::array<std::uint8_t, kFrameBands> symbols{1, 2, 3, 4, 40, 41, 42, 43};
  const auto frame = synthesize_symbols(p, symbols);
  const auto chord = static_cast<std::size_t>(p.bins.chord_samples());
  // The first chord again, at `level` of its amplitude, under the second chord.
  auto lingering = [&](float level) {
    std::vector<float> audio = silence(3000);
    std::vector<float> f = frame;
    for (std::size_t i = 0; i < chord; ++i) f[chord + i] += level * frame[i];
    append(audio, f);
    append(audio, silence(4000));
    for (const auto& c : listen(p, audio)) {
      if (c.symbols == symbols) return true;
    }
    return false;
  };
  EXPECT_FALSE(lingering(0.7f)) << "a note held across both chords";
  EXPECT_TRUE(lingering(0.1f)) << "a reverberant tail 20 dB down";
}

TEST(BinReplyListener, EveryAckNamesItsSequenceNumberAndANackIsANack) {
  const LinkProfile& p = fast_profile();
  BinReplyListener listener(p);
  std::vector<NamedReply> expected, heard;
  for (int s = 0; s <= 16; ++s) {
    const NamedReply reply = s < 16 ? NamedReply{true, static_cast<std::uint8_t>(s)} : NamedReply{false, 0};
    expected.push_back(reply);
    std::vector<float> audio = silence(static_cast<std::size_t>(300 + 97 * s));
    append(audio, synthesize_named_reply(p, reply));
    append(audio, silence(3000));
    for (const auto& h : listener.feed(audio)) heard.push_back(h.reply);
  }
  EXPECT_EQ(heard, expected);
}

TEST(BinReplyListener, NoiseOrAToneInOneBandIsNoReply) {
  const LinkProfile& p = fast_profile();
  BinReplyListener listener(p);
  const std::array<double, 1> tone{(p.bins.reply_band_first_bin[0] + 5) * 48000.0 / p.bins.reply_window_samples};
  std::vector<float> one_band = synthesize_chord(p, tone, 100);
  std::vector<float> audio = silence(1000);
  append(audio, one_band);
  append(audio, silence(3000));
  EXPECT_TRUE(listener.feed(audio).empty());

  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  std::vector<float> hiss(static_cast<std::size_t>(p.sample_rate_hz) * 20);
  for (float& s : hiss) s = noise(rng);
  EXPECT_TRUE(listener.feed(hiss).empty());
}
