// The carrier sense (reliability/carrier_sense.h) on a lone seed sender's own chords, played
// from its loudspeaker 0.1 m beside its microphone in every measured room (bench/rirs): the
// reverberant tail of our own sound is never another's. A pure tone's decay in a room beats
// (its modes interfere), so 5 ms blocks of a tail dip well under its envelope and come back;
// before the tail was judged on its envelope (the loudest block of the last kFloorSmoothMs),
// such a dip made the next blocks a "rise", and a lone sender in the seminar room yielded for a minute
// (dtmf-bench-e2e --profile seed --rir seminar_room_clap.wav --seed 1: 12 yields).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "profile/link_profile.h"
#include "reliability/carrier_sense.h"
#include "signal/synthesizer.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;

namespace {

constexpr int kBlockSamples = 240;            // 5 ms at 48 kHz, the sender's answer hop
constexpr double kOwnSpeakerDistanceM = 0.1;  // as the simulated air puts it (sim/simulated_air.cpp)
constexpr double kAfterFrameMs = 200;         // the seed's gap_ms: our answer came during the chord
constexpr int kFrames = 40;                   // 40 s of frames back to back
constexpr double kPauseEveryMs = 20'000;      // the listening pause (reliability/air_access.h) ...
constexpr double kPauseMs = 700;              // ... of the seed's answer silence

struct LoneSender {
  LoneSender(const std::string& rir, std::uint64_t seed) : profile(profile_by_name("seed")), random(seed) {
    sim::ChannelConfig config;
    config.noise = sim::parse_noise("pink", -50);
    config.room.rir_file = rir;
    config.seed = seed;
    channel = std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config);
    channel->add_transmitter(kOwnSpeakerDistanceM, false);
  }
  // Plays `samples` (silence if empty) for `ms`, feeding each block the microphone records.
  void air(const std::vector<float>& samples, double ms) {
    const auto blocks = static_cast<std::size_t>(ms * profile.sample_rate_hz / 1000.0) / kBlockSamples;
    std::vector<float> out(kBlockSamples), heard;
    for (std::size_t b = 0; b < blocks; ++b) {
      std::fill(out.begin(), out.end(), 0.0f);
      for (std::size_t i = 0; i < out.size(); ++i) {
        const std::size_t at = b * kBlockSamples + i;
        if (at < samples.size()) out[i] = samples[at];
      }
      const std::span<const float> played[] = {out};
      heard.clear();
      channel->process(played, heard);
      t_ms += 1000.0 * kBlockSamples / profile.sample_rate_hz;
      sense.hear(reliability::block_level_dbfs(heard), t_ms);
    }
  }
  void exchange() {
    const auto frame = static_cast<std::uint16_t>(random() & 0xffff);
    sense.own_begin(t_ms);
    air(signal::synthesize_frame(profile, frame), profile.timing.chord_ms);
    sense.frame_ended(t_ms);
    // The robot answered while the chord sounded (its span is in the past).
    sense.own_end(t_ms, reliability::AirSpan{t_ms - 600, t_ms - 300});
    air({}, kAfterFrameMs);
  }

  const LinkProfile& profile;
  std::mt19937_64 random;
  std::unique_ptr<sim::AcousticChannel> channel;
  reliability::CarrierSense sense;
  double t_ms = 0;
};

}  // namespace

TEST(CarrierSenseInRooms, ALoneSeedSendersOwnTailsAreNobodyElsesInEveryMeasuredRoom) {
  int rooms = 0;
  for (const auto& entry : std::filesystem::directory_iterator(DTMF_RIR_DIR)) {
    if (entry.path().extension() != ".wav") continue;
    ++rooms;
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      LoneSender sender(entry.path().string(), seed);
      sender.air({}, 2000);  // the floor
      double paused_at_ms = sender.t_ms;
      for (int f = 0; f < kFrames; ++f) {
        sender.exchange();
        if (sender.t_ms - paused_at_ms >= kPauseEveryMs) {
          sender.air({}, kPauseMs);
          paused_at_ms = sender.t_ms;
        }
      }
      EXPECT_EQ(sender.sense.busy_blocks(), 0u)
          << entry.path().filename() << " seed " << seed << ": blocks of our own tail taken for another's sound";
    }
  }
  EXPECT_EQ(rooms, 9);
}
