// The simulated air in a room: each station at its place, the sound between two stations
// the same both ways (reciprocity), and rooms it cannot use refused.
#include <gtest/gtest.h>

#include <thread>

#include "room_test_support.h"
#include "sim/simulated_air.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

ChannelConfig shoebox_air() {
  ChannelConfig config;
  config.room.shoebox = ShoeboxRoom{};
  config.room.shoebox->size_m = {5, 6, 3};
  config.room.target_rt60_s = 0.3;
  return config;
}

std::size_t loudest(std::span<const float> x) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::abs(x[i]) > std::abs(x[best])) best = i;
  return best;
}

}  // namespace

TEST(SimulatedAirRoom, BetweenTwoStationsTheRoomSoundsTheSameBothWays) {
  SimulatedAir air(kRate, shoebox_air(), 10);
  auto a = air.add_station("sender", 0.0);
  auto b = air.add_station("robot", 2.0);
  air.start();
  // A clicks at once, B half a second later; both microphones record 1.2 s. (However late
  // the threads start, within 0.5 s, each click is found where it landed.)
  const std::size_t half = kRate / 2, recorded = kRate * 6 / 5;
  std::vector<float> click_now(half * 2, 0.0f), click_later(half * 2, 0.0f);
  click_now[0] = 1.0f;
  click_later[half] = 1.0f;
  std::thread play_a([&] { a.speaker->write(click_now); });
  std::thread play_b([&] { b.speaker->write(click_later); });
  std::vector<float> heard_a(recorded), heard_b(recorded);
  std::thread record_a([&] { a.microphone->read(heard_a); });
  b.microphone->read(heard_b);
  record_a.join();
  play_a.join();
  play_b.join();
  air.stop();

  // Each station hears its own loudspeaker first and loudest (0.1 m away, 14 samples late).
  const std::size_t own_a = loudest(std::span(heard_a).first(half));
  const std::size_t own_b = half + loudest(std::span(heard_b).subspan(half));
  ASSERT_LE(own_b + 4800, recorded) << "B's click came too late to compare";
  // A's click reaches B (1.9 m farther than A's own), B's click reaches A: the same response.
  const double apart = (2.0 - 0.1) / kSpeedOfSoundMps * kRate;
  const auto a_to_b = std::span(heard_b).subspan(own_a, 4800);
  const auto b_to_a = std::span(heard_a).subspan(own_b, 4800);
  EXPECT_NEAR(static_cast<double>(loudest(a_to_b)), apart, 3.0);
  // Both stations stand 5 cm above the floor: its reflection arrives with the direct sound
  // (0.4 samples later), so the two add to nearly (1 + 0.97) / 2 m (a little less: they
  // are not quite in step, and air takes 1 dB above 11 kHz over 2 m). Alone it would be 0.5.
  const double peak = peak_near(a_to_b, static_cast<double>(loudest(a_to_b)), 1.0).second;
  EXPECT_NEAR(peak, 0.9, 0.08);
  for (std::size_t i = 0; i < a_to_b.size(); ++i) EXPECT_NEAR(a_to_b[i], b_to_a[i], 2e-3) << i;
}

TEST(SimulatedAirRoom, RoomsItCannotUseAreRefused) {
  ChannelConfig outside = shoebox_air();
  outside.room.mic_at = Point3{2, 7, 1};
  EXPECT_THROW(SimulatedAir(kRate, outside), std::invalid_argument) << "checked when the air is made";
  SimulatedAir air(kRate, shoebox_air());
  air.add_station("sender", 0.0);
  air.add_station("robot", 9.0);  // the room is 5 m long
  try {
    air.start();
    FAIL() << "a station outside the room";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("station 'robot'"), std::string::npos) << e.what();
  }
  ChannelConfig measured;
  measured.room.rir_file = rir_path("studio_live_room.wav");
  SimulatedAir in_measured_room(kRate, measured);
  in_measured_room.add_station("sender", 0.0);
  in_measured_room.add_station("robot", 4.0);
  in_measured_room.start();
}
