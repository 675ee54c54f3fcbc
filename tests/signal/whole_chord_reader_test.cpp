// Signal layer, fast profile: the whole-chord re-read (signal/whole_chord_reader.h) finds
// where a frame's chords begin and at what frequency offset, reads every tone in the grid's
// units, and at -12 dB SNR misreads about half as many tones as the grid's 40 ms windows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "signal/bin_power.h"
#include "signal/hop_synthesizer.h"
#include "signal/whole_chord_reader.h"
#include "sim/acoustic_channel.h"
#include "units/decibels.h"

using namespace dtmf;

namespace {
const LinkProfile& p = fast_profile();
const HopPlan& h = p.hops();
// The listener's bins (hop_listener.cpp): the bands, with room for offsets.
constexpr int kLoBin = 156;
constexpr int kBins = 720 - kLoBin;

signal::HoppedSymbols symbols(unsigned seed) {
  std::mt19937 rng(seed);
  signal::HoppedSymbols s{};
  for (auto& v : s) v = static_cast<std::uint8_t>(rng() % 32);
  return s;
}

// The end of the grid window inside the last chord of a frame starting at sample `start`,
// for a grid whose windows end at multiples of the hop.
long long last_window_end(long long start) {
  const long long first_sample = start + h.chord_samples() + h.edge_samples + h.window_samples;
  return (first_sample + h.hop_samples - 1) / h.hop_samples * h.hop_samples;
}

struct Read {
  std::array<signal::ChordPowers, 3> chords;
  std::optional<signal::WholeChordFit> fit;
  long long steady_start = 0;  // the stream's sample where the fit found the first chord's steady part
};

// Pushes `audio` up to the frame's last grid window and the re-read's delay, then reads.
Read reread(const std::vector<float>& audio, long long frame_start) {
  signal::WholeChordReader reader(h, kLoBin, kBins, 3);
  const long long end = last_window_end(frame_start);
  const long long pushed =
      std::min<long long>(end + h.reread_delay_hops * h.hop_samples, static_cast<long long>(audio.size()));
  reader.push(std::span<const float>(audio).first(static_cast<std::size_t>(pushed)));
  Read r;
  for (auto& c : r.chords) {
    c.power.assign(kBins, 0.0f);
    c.excess.assign(kBins, 0.0f);
  }
  const std::vector<float> none(kBins, 0.0f);
  r.fit = reader.read(pushed - end, 2, none, none, std::span(r.chords).first(3));
  if (r.fit) r.steady_start = pushed - r.fit->steady_start_age;
  return r;
}

// The strongest tone of chord c's band b.
int strongest(const std::vector<float>& power, int c, int b) {
  const auto first =
      power.begin() + (h.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] - kLoBin);
  return static_cast<int>(std::max_element(first, first + h.tones_per_band) - first);
}
}  // namespace

class WholeChordReaderOffset : public ::testing::TestWithParam<double> {};

// At any alignment of the grid and any offset the listener searches: every tone, at its
// level in the grid's units (a tone of amplitude A reads (A W / 2)^2 in a W-point window).
TEST_P(WholeChordReaderOffset, FindsTheChordsAndTheOffsetAndReadsEveryTone) {
  for (int k = 0; k < 4; ++k) {
    const auto sent = symbols(static_cast<unsigned>(k + 1));
    const long long start = 3000 + k * 131;  // other alignments in the hop
    sim::ChannelConfig config;
    config.clock_offset_ppm = -GetParam();  // a slow microphone clock hears tones high
    sim::AcousticChannel channel(p.sample_rate_hz, config);
    channel.add_transmitter(1.0);
    std::vector<float> audio(static_cast<std::size_t>(start), 0.0f), heard;
    const auto frame = signal::synthesize_hopped_frame(p, sent);
    audio.insert(audio.end(), frame.begin(), frame.end());
    audio.resize(audio.size() + 6000, 0.0f);
    channel.process(audio, heard);
    // The metre from the loudspeaker delays the frame by 140 samples (1 m / 343 m/s at 48 kHz).
    const long long heard_start = start + std::lround(p.sample_rate_hz / 343.0);
    const Read r = reread(heard, heard_start);
    ASSERT_TRUE(r.fit);
    EXPECT_NEAR(r.fit->offset_ppm, GetParam(), 150) << "frame " << k;
    // Where the robot logs the frame as begun: within a search step of its steady part.
    EXPECT_NEAR(r.steady_start, heard_start + h.edge_samples, h.reread_step_samples) << "frame " << k;
    const double tone_power = std::pow(h.tone_amplitude * h.window_samples / 2, 2);
    for (int c = 0; c < 2; ++c) {
      for (int b = 0; b < 8; ++b) {
        const int t = c * 8 + b;
        const auto& power = r.chords[static_cast<std::size_t>(c + 1)].power;
        EXPECT_EQ(strongest(power, c, b), sent[static_cast<std::size_t>(t)]) << "frame " << k << " tone " << t;
        const auto bin = h.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] +
                         sent[static_cast<std::size_t>(t)] - kLoBin;
        // Within 1.5 dB: the channel's device response, and up to an eighth of a bin's rounding.
        EXPECT_NEAR(units::db_from_power_ratio(power[static_cast<std::size_t>(bin)] / tone_power), 0.0, 1.5)
            << "frame " << k << " tone " << t;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Ppm, WholeChordReaderOffset,
                         ::testing::Values(-3000.0, -1200.0, -600.0, 0.0, 400.0, 700.0, 2000.0));

// 1 dB more per tone: at -12 dB SNR the grid's window inside each chord misreads 12.8 % of
// tones (32-ary noncoherent detection at 8.8 dB per bin), the whole chord about 6 % with its
// start known and about 7 % as found.
TEST(WholeChordReader, AtMinusTwelveDbItMisreadsAboutHalfAsManyTonesAsTheGrid) {
  constexpr int kFrames = 120;
  std::mt19937 rng(21);
  signal::BinPower grid(h.window_samples, kLoBin, kBins);
  std::vector<float> grid_power(kBins);
  int grid_wrong = 0, whole_wrong = 0;
  for (int k = 0; k < kFrames; ++k) {
    const auto sent = symbols(static_cast<unsigned>(100 + k));
    const long long start = 4000 + static_cast<long long>(rng() % static_cast<unsigned>(h.hop_samples));
    const auto frame = signal::synthesize_hopped_frame(p, sent);
    double power = 0;
    for (const float s : frame) power += static_cast<double>(s) * s;
    power /= static_cast<double>(frame.size());
    std::vector<float> audio(static_cast<std::size_t>(start), 0.0f);
    audio.insert(audio.end(), frame.begin(), frame.end());
    audio.resize(audio.size() + 6000, 0.0f);
    std::normal_distribution<float> noise(0.0f, static_cast<float>(std::sqrt(power / units::power_ratio_from_db(-12))));
    for (float& s : audio) s += noise(rng);
    const Read r = reread(audio, start);
    ASSERT_TRUE(r.fit);
    const long long end = last_window_end(start);
    for (int c = 0; c < 2; ++c) {
      const long long window_end = end - (1 - c) * h.chord_samples();
      grid.analyze(std::span<const float>(audio).subspan(static_cast<std::size_t>(window_end - h.window_samples),
                                                         static_cast<std::size_t>(h.window_samples)),
                   grid_power);
      for (int b = 0; b < 8; ++b) {
        const int s = sent[static_cast<std::size_t>(c * 8 + b)];
        grid_wrong += strongest(grid_power, c, b) != s;
        whole_wrong += strongest(r.chords[static_cast<std::size_t>(c + 1)].power, c, b) != s;
      }
    }
  }
  const double tones = kFrames * 16.0;
  std::printf("-12 dB: the grid misread %.1f %% of %d tones, the whole chords %.1f %%\n", 100 * grid_wrong / tones,
              kFrames * 16, 100 * whole_wrong / tones);
  EXPECT_GT(grid_wrong, tones * 0.08);
  EXPECT_LT(grid_wrong, tones * 0.18);
  EXPECT_LT(whole_wrong, grid_wrong * 0.75);
}

TEST(WholeChordReader, AFrameNoLongerInTheHistoryIsNotRead) {
  signal::WholeChordReader reader(h, kLoBin, kBins, 3);
  reader.push(std::vector<float>(static_cast<std::size_t>(reader.history_samples()) * 2, 0.0f));
  std::array<signal::ChordPowers, 3> out;
  for (auto& c : out) {
    c.power.assign(kBins, 0.0f);
    c.excess.assign(kBins, 0.0f);
  }
  const std::vector<float> none(kBins, 0.0f);
  EXPECT_TRUE(reader.read(h.reread_delay_hops * h.hop_samples, 2, none, none, out));
  EXPECT_FALSE(reader.read(reader.history_samples(), 2, none, none, out));
}
