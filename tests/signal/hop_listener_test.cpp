// Signal layer, fast profile: the hopped frame listener and the reply listener read what the
// synthesizer wrote — every tone of every band at any alignment of the analysis grid, at any
// frequency offset the clocks and Doppler give — and take out what is no tone of a frame:
// noise, a steady whine, a reverberant tail, a held chord.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "link/link.h"
#include "reliability/command_frame.h"
#include "reliability/reply_code.h"
#include "signal/hop_listener.h"
#include "signal/hop_reply.h"
#include "signal/hop_synthesizer.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;

namespace {
const LinkProfile& p = fast_profile();

std::vector<signal::HopCandidate> candidates(const std::vector<float>& audio, signal::HopListener& listener) {
  std::vector<signal::HopCandidate> got;
  for (std::size_t at = 0; at < audio.size(); at += 480) {
    for (const auto& c :
         listener.feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(480, audio.size() - at)))) {
      got.push_back(c);
    }
  }
  return got;
}

// How many of the frame's sixteen symbols the best candidate (ignoring offset hypotheses)
// reads right, and how many of those it heard.
std::pair<int, int> best_reading(const std::vector<signal::HopCandidate>& got, const signal::HoppedSymbols& sent) {
  std::pair<int, int> best{0, 0};
  for (const auto& c : got) {
    int right = 0, heard = 0;
    for (std::size_t t = 0; t < sent.size(); ++t) {
      right += c.tones[t].symbol == sent[t];
      heard += c.tones[t].symbol == sent[t] && c.tones[t].heard;
    }
    best = std::max(best, std::make_pair(right, heard));
  }
  return best;
}

std::vector<float> with_silence(const std::vector<float>& audio, std::size_t before, std::size_t after) {
  std::vector<float> out(before, 0.0f);
  out.insert(out.end(), audio.begin(), audio.end());
  out.resize(out.size() + after, 0.0f);
  return out;
}

void add_sine(std::vector<float>& audio, double hz, double amplitude) {
  for (std::size_t i = 0; i < audio.size(); ++i) {
    audio[i] +=
        static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * hz * static_cast<double>(i) / p.sample_rate_hz));
  }
}

}  // namespace

TEST(HopListener, EveryToneOfEveryBandIsReadBackAtAnyAlignment) {
  // Symbol v in every band, for every v, each frame starting at another sample of the hop.
  for (int v = 0; v < p.hops().tones_per_band; ++v) {
    signal::HoppedSymbols sent{};
    sent.fill(static_cast<std::uint8_t>(v));
    const std::size_t offset = static_cast<std::size_t>(v * 37 % p.hops().hop_samples);
    signal::HopListener listener(p);
    const auto got = candidates(with_silence(signal::synthesize_hopped_frame(p, sent), 3000 + offset, 6000), listener);
    const auto [right, heard] = best_reading(got, sent);
    EXPECT_EQ(right, 16) << "symbol " << v;
    EXPECT_EQ(heard, 16) << "symbol " << v;
  }
}

// A listener that starts as a frame starts (an agent restarted mid-run) takes what came before
// as silence: the frame's first window is read, not only the late ones that straddle its end.
TEST(HopListener, AFrameFromTheVeryFirstSampleIsRead) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((7 * t + 3) % 32);
  signal::HopListener listener(p);
  const auto got = candidates(with_silence(signal::synthesize_hopped_frame(p, sent), 0, 6000), listener);
  std::vector<signal::HopCandidate> at_start;
  std::copy_if(got.begin(), got.end(), std::back_inserter(at_start),
               [](const signal::HopCandidate& c) { return c.chords == 2 && c.start_ms < 12.0; });
  ASSERT_FALSE(at_start.empty()) << "no candidate begins with the frame";
  const auto [right, heard] = best_reading(at_start, sent);
  EXPECT_EQ(right, 16);
  EXPECT_EQ(heard, 16);
}

TEST(HopListener, NoiseAloneSeldomMakesACandidate) {
  std::vector<float> noise(static_cast<std::size_t>(p.sample_rate_hz) * 20);
  std::mt19937 rng(3);
  std::normal_distribution<float> gauss(0.0f, 0.05f);
  for (float& s : noise) s = gauss(rng);
  signal::HopListener listener(p);
  const auto got = candidates(noise, listener);
  const auto rereads = std::count_if(got.begin(), got.end(), [](const auto& c) { return c.whole_chords; });
  const auto grid = std::count_if(got.begin(), got.end(), [](const auto& c) { return !c.second_look; });
  // 20 s is about 1950 windows; each gated window costs a decode, so the gate must hold.
  EXPECT_LE(grid, 6);
  // Failed windows, and windows short of the gate by a band, are read again over whole
  // chords (about 0.15 ms each): white noise passes for that about once in 200 windows.
  EXPECT_LE(rereads, 12);
}

// A chord whose tones carry on into the next chord's time is no frame's first chord: its
// tones did not start there. A room's decaying tail does not start either.
TEST(HopListener, AToneThatDoesNotStartWithItsChordIsNotHeard) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((5 * t + 3) % 32);
  const auto frame = signal::synthesize_hopped_frame(p, sent);
  // The first chord, then the whole frame: the second time, chord one's tones were already there.
  std::vector<float> audio(frame.begin(), frame.begin() + p.hops().chord_samples());
  audio.insert(audio.end(), frame.begin(), frame.end());
  signal::HopListener listener(p);
  const auto got = candidates(with_silence(audio, 3000, 6000), listener);
  // The frame's own alignment: its second chord's inner window ends about here, and the frame
  // began here. A whole-chord re-read is heard a few hops after its window but knows where the
  // frame began: those that found it within half a hop. (One of a window a hop late, its search
  // clamped to that hop, finds it 10 ms late, where its onset reference straddles both copies.)
  const double aligned_ms =
      (3000.0 + 2 * p.hops().chord_samples() + p.hops().edge_samples + p.hops().window_samples) / 48.0;
  const double begun_ms = (3000.0 + p.hops().chord_samples()) / 48.0;
  int checked = 0, rereads = 0;
  for (const auto& c : got) {
    // (A grid reading offered again for a second look was checked at its first.)
    if (c.chords != 2 || (c.second_look && !c.whole_chords)) continue;
    if (c.whole_chords ? std::abs(c.start_ms - begun_ms) > p.hops().hop_samples / 96.0
                       : std::abs(c.heard_ms - aligned_ms) > 15)
      continue;
    rereads += c.whole_chords;
    ++checked;
    int first_chord_heard = 0;
    for (int b = 0; b < 8; ++b)
      first_chord_heard += c.tones[static_cast<std::size_t>(b)].heard &&
                           c.tones[static_cast<std::size_t>(b)].symbol == sent[static_cast<std::size_t>(b)];
    EXPECT_LE(first_chord_heard, 0) << "at " << c.heard_ms << " ms";
  }
  EXPECT_GT(checked, 0) << "no candidate at the frame's alignment to check";
  EXPECT_GT(rereads, 0) << "no whole-chord re-read at the frame's alignment to check";
}

// A whine 6 dB over a tone, right on a tone of the plan: the background takes it, the symbol
// is still read and heard.
TEST(HopListener, ASteadyWhineOnAToneOfThePlanBecomesBackground) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((7 * t + 1) % 32);
  const double whine_hz = (p.hops().band_first_bin[0][3] + 20) * 25.0;  // band 3 of chord one, not the sent tone
  std::vector<float> audio = with_silence(signal::synthesize_hopped_frame(p, sent), 48000 * 3, 6000);
  add_sine(audio, whine_hz, 2 * p.hops().tone_amplitude);
  signal::HopListener listener(p);
  const auto [right, heard] = best_reading(candidates(audio, listener), sent);
  EXPECT_EQ(right, 16);
  EXPECT_GE(heard, 15);
}

class HopListenerOffset : public ::testing::TestWithParam<double> {};

// Clocks and Doppler move every tone by the same factor: the listener finds it from one frame.
TEST_P(HopListenerOffset, TheBlindOffsetEstimateReadsEverySymbolAndConfirmTracksIt) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((11 * t + 4) % 32);
  sim::ChannelConfig config;
  config.clock_offset_ppm = -GetParam();  // the microphone's clock: a slow clock hears tones high
  sim::AcousticChannel channel(p.sample_rate_hz, config);
  channel.add_transmitter(1.0);
  std::vector<float> heard;
  channel.process(with_silence(signal::synthesize_hopped_frame(p, sent), 3000, 6000), heard);
  signal::HopListener listener(p);
  const auto got = candidates(heard, listener);
  // The window wholly inside both chords: its second chord's inner window ends about here.
  const double aligned_ms = (3000.0 + 2 * p.hops().chord_samples() - p.hops().hop_samples) / 48.0;
  const signal::HopCandidate* aligned = nullptr;
  int right_aligned = 0;
  for (const auto& c : got) {
    int right = 0;
    for (std::size_t t = 0; t < sent.size(); ++t) right += c.tones[t].symbol == sent[t];
    // Of the grid's candidates nearest the alignment, the hypothesis that reads the frame.
    if (!c.whole_chords && std::abs(c.heard_ms - aligned_ms) <= 6 && right > right_aligned) {
      right_aligned = right;
      aligned = &c;
    }
  }
  ASSERT_NE(aligned, nullptr) << "no candidate at " << aligned_ms << " ms";
  EXPECT_EQ(right_aligned, 16) << "at " << GetParam() << " ppm";
  listener.confirm(*aligned, sent);
  ASSERT_TRUE(listener.tracked_offset_ppm());
  EXPECT_NEAR(*listener.tracked_offset_ppm(), GetParam(), 150);  // 0.1 bin at 17 kHz
  // A window astride a chord's edge decodes too, but tells nothing reliable of the offset.
  signal::HopListener fresh(p);
  const auto early = candidates(heard, fresh);
  fresh.confirm(early.front(), sent);
  if (fresh.tracked_offset_ppm()) {
    EXPECT_NEAR(*fresh.tracked_offset_ppm(), GetParam(), 300);
  }
}

INSTANTIATE_TEST_SUITE_P(Ppm, HopListenerOffset,
                         ::testing::Values(-3000.0, -2000.0, -700.0, 0.0, 900.0, 2000.0, 3000.0));

namespace {
// What the sender's ear (the fast link's answer listener) hears in `audio`, fed in reply hops;
// `keyed`: a sender with a key, which listens for tagged ACKs.
std::vector<link::Answer> answers_heard(const std::vector<float>& audio, bool keyed = false) {
  link::LinkOptions options;
  if (keyed) options.key = security::LinkKey::generate();
  const auto ear = link::make_link(p, options)->answer_listener();
  std::vector<link::Answer> got;
  const auto hop = static_cast<std::size_t>(p.hops().reply_hop_samples);
  for (std::size_t at = 0; at < audio.size(); at += hop) {
    for (const auto& a : ear->feed(std::span<const float>(audio).subspan(at, std::min(hop, audio.size() - at)))) {
      got.push_back(a);
    }
  }
  return got;
}

std::vector<float> reply_audio(const reliability::ReplyTones& tones, int lane = 0) {
  return signal::synthesize_hopped_reply(p, tones, lane);
}
}  // namespace

TEST(HopReplyListener, EveryAckNamesItsSequenceNumberAndANackIsANack) {
  std::vector<float> audio(2000, 0.0f);
  for (int r = 0; r <= 16; ++r) {
    // ACK(s) sounds in lane s % 2, NACK in lane 0 (link/fast_link.cpp).
    const auto reply =
        reply_audio(reliability::reply_codeword({r < 16, static_cast<std::uint8_t>(r % 16)}), r % 16 % 2);
    audio.insert(audio.end(), reply.begin(), reply.end());
    audio.insert(audio.end(), 4800, 0.0f);
  }
  std::vector<int> named;
  for (const auto& a : answers_heard(audio)) {
    if (!a.tag_reading) named.push_back(a.ack ? *a.sequence : 16);
  }
  std::vector<int> expected(17);
  std::iota(expected.begin(), expected.end(), 0);
  EXPECT_EQ(named, expected);
}

// Three of the ten tones lost or misread (a fade, a click) and the reply is still itself;
// pure noise is no reply at all.
TEST(HopReplyListener, AReplyWithThreeTonesGoneIsStillHeardAndNoiseIsNoReply) {
  auto tones = reliability::reply_codeword({true, 9});
  std::vector<float> audio(2000, 0.0f);
  const auto full = reply_audio(tones, 1);
  audio.insert(audio.end(), full.begin(), full.end());
  audio.insert(audio.end(), 4800, 0.0f);
  // Each misread as another of its band's tones: a value past them would index past the
  // band's bins (reply_bin), into the next band's.
  for (std::size_t t : {1u, 4u, 8u}) {
    tones[t] = static_cast<std::uint8_t>((tones[t] + 3) % HopPlan::kReplyToneValues);
  }
  const auto damaged = reply_audio(tones, 1);
  audio.insert(audio.end(), damaged.begin(), damaged.end());
  audio.insert(audio.end(), 4800, 0.0f);
  std::vector<int> named;
  for (const auto& a : answers_heard(audio)) {
    if (!a.tag_reading) named.push_back(a.ack ? *a.sequence : 16);
  }
  EXPECT_EQ(named, (std::vector<int>{9, 9}));
  std::vector<float> noise(48000 * 5);
  std::mt19937 rng(5);
  std::normal_distribution<float> gauss(0.0f, 0.1f);
  for (float& x : noise) x = gauss(rng);
  EXPECT_TRUE(answers_heard(noise).empty());
}

// The seed's ACK and NACK tones (2000, 2500, 3000, 3500 Hz) are no reply tone in either lane, so
// no fast reply sounds like a seed answer; a seed ACK lies within a bin of one tone of each lane
// at most (a seed ACK played beside the sender costs an answer at most that tone); every reply
// tone lies below 3.5 kHz.
TEST(ReplyCode, NoReplyToneIsASeedAnswerTone) {
  const double bin_hz = static_cast<double>(p.sample_rate_hz) / p.hops().reply_window_samples;
  for (int lane = 0; lane < HopPlan::kReplyLanes; ++lane) {
    int near_seed_ack = 0;
    for (int b = 0; b < HopPlan::kReplyBands; ++b) {
      for (int v = 0; v < HopPlan::kReplyToneValues; ++v) {
        const double hz = p.hops().reply_bin(lane, b, v) * bin_hz;
        EXPECT_LT(hz, 3500.0) << "the top reply tone stays well below the frames' 4 kHz";
        for (double seed_hz : {2000.0, 2500.0, 3000.0, 3500.0}) EXPECT_NE(hz, seed_hz) << "lane " << lane;
        for (double ack_hz : {2500.0, 3500.0}) near_seed_ack += std::abs(hz - ack_hz) <= bin_hz ? 1 : 0;
      }
    }
    EXPECT_LE(near_seed_ack, 1) << "lane " << lane;
  }
}

namespace {
// A two-chord frame with chord one's tones in only `bands` of its eight bands (tones on grid
// bins, each chord faded in and out over the plan's edges), in light white noise.
std::vector<float> frame_with_bands_missing(const signal::HoppedSymbols& sent, int bands, unsigned seed) {
  const auto chord = static_cast<std::size_t>(p.hops().chord_samples());
  std::vector<float> audio(3000 + 2 * chord + 9000, 0.0f);
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < (c == 0 ? 8 : bands); ++b) {
      const int bin = p.hops().band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] +
                      sent[static_cast<std::size_t>(c * 8 + b)];
      for (std::size_t i = 0; i < chord; ++i) {
        const std::size_t near = std::min(i, chord - 1 - i);
        const double fade =
            near < static_cast<std::size_t>(p.hops().edge_samples)
                ? 0.5 - 0.5 * std::cos(std::numbers::pi * (static_cast<double>(near) + 0.5) / p.hops().edge_samples)
                : 1.0;
        audio[3000 + static_cast<std::size_t>(c) * chord + i] += static_cast<float>(
            p.hops().tone_amplitude * fade *
            std::sin(2 * std::numbers::pi * bin * static_cast<double>(i) / p.hops().window_samples + b));
      }
    }
  }
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (float& s : audio) s += noise(rng);
  return audio;
}
}  // namespace

// At the frame's own alignment (the grid window wholly inside each chord), three loud bands in
// chord one (and half of all bands loud) are short of the gate: the grid's readings are not
// decoded, but the window is read again over whole chords, as a frame at -12 dB whose weaker
// chord missed the gate by a band is. Two loud bands make nothing there. (Windows astride the
// chords' edges spread every tone over all bands and pass either way: not looked at here.)
TEST(HopListener, AWindowABandShortOfTheGateIsOnlyReadAgainOverWholeChords) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((13 * t + 2) % 32);
  const double aligned_ms = (3000.0 + 2 * p.hops().chord_samples() - p.hops().hop_samples) / 48.0;
  // A re-read is heard when it is made, its delay after the window; and it knows where the
  // frame began (sample 3000) closer than the grid's half a hop.
  const double reread_ms = aligned_ms + p.hops().reread_delay_hops * p.hops().hop_samples / 48.0;
  for (const int bands : {3, 2}) {
    signal::HopListener listener(p);
    const auto got = candidates(frame_with_bands_missing(sent, bands, 5), listener);
    int grid = 0, whole = 0, best_right = 0;
    for (const auto& c : got) {
      if (c.chords != 2 || (c.second_look && !c.whole_chords)) continue;
      if (std::abs(c.heard_ms - (c.whole_chords ? reread_ms : aligned_ms)) > 3) continue;
      if (c.whole_chords) {
        EXPECT_NEAR(c.start_ms, 3000.0 / 48.0, p.hops().reread_step_samples / 48.0);
      }
      (c.whole_chords ? whole : grid) += 1;
      int right = 0;
      for (int t = 0; t < 8 + bands; ++t)
        right += c.tones[static_cast<std::size_t>(t)].symbol == sent[static_cast<std::size_t>(t)];
      if (c.whole_chords) best_right = std::max(best_right, right);
    }
    EXPECT_EQ(grid, 0) << bands << " loud bands in chord one";
    if (bands == 3) {
      EXPECT_EQ(whole, 1);
      EXPECT_EQ(best_right, 11) << "every tone sent, read over whole chords";
    } else {
      EXPECT_EQ(whole, 0);
    }
  }
}

namespace {
// Takes a candidate when it reads every tone of `sent` right and heard (as a decoder would
// take a clean frame), or nothing at all; keeps every candidate offered.
struct TakeClean final : signal::CandidateSink {
  signal::HoppedSymbols sent{};
  bool takes = true;
  std::vector<signal::HopCandidate> offered;
  double delay_ms = p.hops().reread_delay_hops * 1000.0 * p.hops().hop_samples / p.sample_rate_hz;
  double taken_ms = -1;  // the end of the window the frame was taken from
  // The end of the window a candidate reads (a second look comes a delay after it).
  double window_ms(const signal::HopCandidate& c) const { return c.heard_ms - (c.second_look ? delay_ms : 0); }
  bool take(const signal::HopCandidate& c) override {
    offered.push_back(c);
    if (!takes || c.chords != 2) return false;
    for (std::size_t t = 0; t < sent.size(); ++t) {
      if (c.tones[t].symbol != sent[t] || !c.tones[t].heard) return false;
    }
    taken_ms = window_ms(c);
    return true;
  }
  bool none_taken(const signal::HopCandidate&) override { return true; }
};
}  // namespace

// A clean frame's window a hop early straddles a chord's edge and fails; the next window
// takes the frame, and the failed one gets no second look (the sink's costlier decoding of
// it would be wasted). Had nothing been taken, every failed window would get one, its grid
// readings offered again as they were, `reread_delay_hops` later.
TEST(HopListener, AFailedWindowGetsASecondLookOnlyWhenNothingWasTakenAfterIt) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((3 * t + 7) % 32);
  std::mt19937 rng(9);
  std::normal_distribution<float> noise(0.0f, 0.005f);
  int cases_with_a_failed_window = 0;
  for (int offset = 0; offset < p.hops().hop_samples; offset += 41) {
    auto audio = with_silence(signal::synthesize_hopped_frame(p, sent), 3000 + static_cast<std::size_t>(offset), 6000);
    for (float& s : audio) s += noise(rng);
    TakeClean taking, refusing;
    taking.sent = refusing.sent = sent;
    refusing.takes = false;
    signal::HopListener a(p), b(p);
    for (std::size_t at = 0; at < audio.size(); at += 480) {
      const auto block = std::span<const float>(audio).subspan(at, std::min<std::size_t>(480, audio.size() - at));
      a.feed(block, taking);
      b.feed(block, refusing);
    }
    ASSERT_GE(taking.taken_ms, 0) << "offset " << offset << ": the frame was not taken";
    const auto failed_first = std::count_if(taking.offered.begin(), taking.offered.end(), [&](const auto& c) {
      return !c.second_look && c.heard_ms < taking.taken_ms;
    });
    cases_with_a_failed_window += failed_first > 0;
    // (Noise alone passes the gate now and then, after the frame too: those windows are not its.)
    for (const auto& c : taking.offered) {
      EXPECT_FALSE(c.second_look && taking.window_ms(c) < taking.taken_ms)
          << "offset " << offset << ": a second look at the window ending " << taking.window_ms(c)
          << " ms, before the one taken (" << taking.taken_ms << " ms)";
    }

    // Refused, each failed window's hypotheses come again, the same readings, a delay later.
    std::vector<const signal::HopCandidate*> first, second;
    for (const auto& c : refusing.offered) {
      if (!c.whole_chords) (c.second_look ? second : first).push_back(&c);
    }
    ASSERT_EQ(second.size(), first.size()) << "offset " << offset;
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_NEAR(second[i]->heard_ms, first[i]->heard_ms + refusing.delay_ms, 0.01);
      EXPECT_EQ(second[i]->offset_ppm, first[i]->offset_ppm);
      for (std::size_t t = 0; t < sent.size(); ++t) EXPECT_EQ(second[i]->tones[t].symbol, first[i]->tones[t].symbol);
    }
  }
  EXPECT_GT(cases_with_a_failed_window, 0) << "no alignment had a window fail before the frame's own";
}

// The listener's two states: after a take, the sink holds it (HoldFrame) and it offers nothing,
// whatever it hears, until the hold ends; then it detects frames again (DetectFrame).
TEST(HopListener, HeldAfterAFrameItOffersNothingUntilTheHoldEnds) {
  signal::HoppedSymbols sent{};
  for (std::size_t t = 0; t < sent.size(); ++t) sent[t] = static_cast<std::uint8_t>((5 * t + 2) % 32);
  const auto frame = with_silence(signal::synthesize_hopped_frame(p, sent), 4000, 8000);
  std::vector<float> two = frame;
  two.insert(two.end(), frame.begin(), frame.end());  // the second frame starts 400 ms after the first
  const double second_starts_ms = 1000.0 * static_cast<double>(frame.size() + 4000) / p.sample_rate_hz;

  // Takes clean frames and holds the listener `hold_ms` past each one's window.
  struct Holding final : signal::CandidateSink {
    signal::HopListener& listener;
    TakeClean clean;
    double hold_ms;
    std::vector<double> taken_ms;
    std::vector<signal::HopListener::Phase> phase_after;
    Holding(signal::HopListener& l, const signal::HoppedSymbols& s, double hold) : listener(l), hold_ms(hold) {
      clean.sent = s;
    }
    bool take(const signal::HopCandidate& c) override {
      EXPECT_EQ(listener.phase(), signal::HopListener::Phase::DetectFrame) << "a candidate offered while held";
      if (!clean.take(c)) return false;
      taken_ms.push_back(c.heard_ms);
      listener.hold_until(c.heard_ms + hold_ms);
      return true;
    }
    bool none_taken(const signal::HopCandidate&) override { return true; }
  };
  for (const double hold_ms : {100.0, 1000.0}) {
    signal::HopListener listener(p);
    Holding sink(listener, sent, hold_ms);
    for (std::size_t at = 0; at < two.size(); at += 480) {
      listener.feed(std::span<const float>(two).subspan(at, std::min<std::size_t>(480, two.size() - at)), sink);
      if (!sink.taken_ms.empty() && listener.now_ms() < sink.taken_ms.front() + hold_ms) {
        EXPECT_EQ(listener.phase(), signal::HopListener::Phase::HoldFrame) << listener.now_ms();
      }
    }
    if (hold_ms < 400) {
      ASSERT_EQ(sink.taken_ms.size(), 2u) << "a short hold: both frames taken";
      EXPECT_GT(sink.taken_ms[1], second_starts_ms);
      EXPECT_EQ(listener.phase(), signal::HopListener::Phase::DetectFrame);
    } else {
      EXPECT_EQ(sink.taken_ms.size(), 1u) << "a hold past the second frame: it is not offered";
    }
  }
}
