// The whole channel with every effect at once: the same samples for any split of the
// stream, the same for a seed, different for another, and fast enough for benchmarks;
// image-source rooms placed by distance; configurations that cannot work refused.
#include <gtest/gtest.h>

#include <chrono>

#include "physical/audio_io.h"
#include "room_test_support.h"
#include "sim/room_decay.h"

using namespace dtmf::sim;
using namespace dtmf::physical;
using namespace dtmf::room_test;

namespace {

ChannelConfig everything(std::uint64_t seed) {
  ChannelConfig config;
  config.room.shoebox = ShoeboxRoom{};
  config.room.shoebox->size_m = {5, 6, 3};
  config.room.target_rt60_s = 0.5;
  config.speaker_response = response_preset("small-speaker");
  config.mic_response = response_preset("cheap-mic");
  config.noise = parse_noise("pink", -50);
  config.whines = {{9500, -45}};
  config.motion = {0.22, 0.5, 4};
  config.clock_offset_ppm = 120;
  config.seed = seed;
  return config;
}

std::vector<float> run(const ChannelConfig& config, std::span<const float> in, std::size_t block) {
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(2.0);
  return through(channel, in, block);
}

}  // namespace

TEST(ChannelStreaming, AnySplitOfTheStreamGivesTheSameSamplesAndASeedTheSameNoise) {
  const auto in = tone(7000, 1.5, 0.3);
  const auto whole = run(everything(1), in, in.size());
  for (std::size_t block : {1u, 480u, 1023u, 8192u})
    EXPECT_EQ(run(everything(1), in, block), whole) << "blocks of " << block;
  EXPECT_NE(run(everything(2), in, 480), whole) << "another seed, other noise";
}

TEST(ChannelStreaming, AnImageSourceRoomPutsTheLoudspeakerAtTheDistanceAsked) {
  ChannelConfig config;
  config.room.shoebox = ShoeboxRoom{};
  config.room.shoebox->randomization_m = 0;
  AcousticChannel channel(kRate, config);
  const double d = 3.0;
  channel.add_transmitter(d);
  const auto h = impulse_response(channel, 0.5);
  // The direct sound at d / c (the floor's reflection follows 3.7 samples later; their
  // levels are image_source_room_test's business).
  const double expected = d / kSpeedOfSoundMps * kRate;
  EXPECT_NEAR(peak_near(h, expected, 1.5).first, expected, 1.0);
  EXPECT_LT(rms(std::span(h).first(static_cast<std::size_t>(expected) - 40)), 1e-4) << "nothing before it";
  const Point3 mic = channel.room()->microphone();
  EXPECT_DOUBLE_EQ(mic.z, 0.05) << "a robot's microphone by default";
  EXPECT_NEAR(distance_m(channel.room()->speaker_at_distance(d), mic), d, 1e-9);
  EXPECT_THROW(channel.add_transmitter(30.0), std::invalid_argument) << "does not fit in 7 x 9 x 3 m";
}

TEST(ChannelStreaming, ConfigurationsThatCannotWorkAreRefused) {
  ChannelConfig both;
  both.room.rir_file = rir_path("seminar_room_clap.wav");
  both.room.shoebox = ShoeboxRoom{};
  EXPECT_THROW(AcousticChannel(kRate, both), std::invalid_argument);
  ChannelConfig room_and_reverb;
  room_and_reverb.room.rir_file = rir_path("seminar_room_clap.wav");
  room_and_reverb.reverb.rt60_s = 0.4;
  EXPECT_THROW(AcousticChannel(kRate, room_and_reverb), std::invalid_argument);
  ChannelConfig outside;
  outside.room.shoebox = ShoeboxRoom{};
  outside.room.mic_at = Point3{8, 1, 1};
  EXPECT_THROW(AcousticChannel(kRate, outside), std::invalid_argument);
  ChannelConfig missing;
  missing.room.rir_file = "/nonexistent.wav";
  EXPECT_THROW(AcousticChannel(kRate, missing), AudioError);
  ChannelConfig fast;
  fast.clock_offset_ppm = 20000;
  EXPECT_THROW(AcousticChannel(kRate, fast), std::invalid_argument);
  ChannelConfig moving;
  moving.motion = {0.2, 1.0, 3.0};
  AcousticChannel channel(kRate, moving);
  EXPECT_THROW(channel.add_transmitter(5.0), std::invalid_argument) << "starts outside its range";
  channel.add_transmitter(5.0, false);  // a transmitter that does not move may stand anywhere
}

TEST(ChannelStreaming, ALongRoomStreamsManyTimesFasterThanRealTime) {
  ChannelConfig config;
  config.room.rir_file = rir_path("smoking_room.wav");
  config.mic_response = response_preset("cheap-mic");
  config.noise = parse_noise("white", -60);
  AcousticChannel channel(kRate, config);
  channel.add_transmitter(1.0);
  const auto in = tone(8000, 10.0, 0.3);
  const auto start = std::chrono::steady_clock::now();
  const auto out = through(channel, in, 480);
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ figures  ] smoking room (%.2f s response) + cheap mic + noise, 10 ms blocks: %.0f x real time\n",
              channel.ring_out_s(), 10.0 / took_s);
  EXPECT_GT(10.0 / took_s, 20.0);
}
