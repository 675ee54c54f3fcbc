// Reverberation time: a room tuned to an RT60 has it (Schroeder's backward integration,
// T20), and each octave band decays as fast as its walls' reflection says.
#include <gtest/gtest.h>

#include <optional>

#include "room_test_support.h"
#include "sim/image_source_room.h"
#include "sim/room_calibration.h"
#include "sim/room_decay.h"
#include "units/decibels.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

TEST(RoomDecay, T20OfAnExponentialDecayIsItsRt60) {
  // Noise decaying 60 dB in 0.7 s: the measure itself, before any room.
  std::vector<float> h(kRate * 2);
  std::uint64_t state = 1;
  for (std::size_t i = 0; i < h.size(); ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
    h[i] = static_cast<float>(u * dtmf::units::amplitude_ratio_from_db(-60.0 * static_cast<double>(i) / kRate / 0.7));
  }
  const auto rt60 = rt60_t20_s(h, kRate);
  ASSERT_TRUE(rt60);
  EXPECT_NEAR(*rt60, 0.7, 0.02);
  EXPECT_FALSE(rt60_t20_s(std::vector<float>(100, 0.5f), kRate)) << "no decay, no RT60";
}

TEST(RoomDecay, ATunedRoomMeasuresTheRt60AskedFor) {
  struct Case {
    Point3 size;
    double rt60_s;
  };
  for (const Case& c : {Case{{4, 5, 2.7}, 0.3}, Case{{6, 8, 3}, 0.8}}) {
    ShoeboxRoom room;
    room.size_m = c.size;
    const Point3 mic{1.0, 0.4 * c.size.y, 0.05}, speaker{c.size.x - 1.2, c.size.y - 1.1, 0.8};
    const CalibratedRoom tuned = calibrate_rt60(room, speaker, mic, c.rt60_s, kRate, 3);
    const auto h = image_source_response(tuned.room, speaker, mic, kRate, 3);
    const auto rt60 = rt60_t20_s(h, kRate);
    ASSERT_TRUE(rt60);
    std::printf("[ figures  ] %gx%gx%g m asked RT60 %.2f s: walls %.4f, T20 %.3f s (Eyring %.2f s), %.2f s long\n",
                c.size.x, c.size.y, c.size.z, c.rt60_s, tuned.reflection, *rt60, eyring_rt60_s(tuned.room),
                static_cast<double>(h.size()) / kRate);
    EXPECT_NEAR(*rt60, c.rt60_s, 0.1 * c.rt60_s);
    // Generated until it has decayed 60 dB: the last sample is far below the first.
    EXPECT_LE(decay_point(h, 60.0), h.size());
  }
}

TEST(RoomDecay, EachOctaveBandDecaysAsFastAsItsReflectionSays) {
  // Two rooms whose bands alternate between 0.85 and 0.95, the other way round, all
  // surfaces alike, no air (only the walls decide). In each band the room reflecting less
  // decays faster; within a room every 0.85 band is shorter than every 0.95 band. (Bands
  // are compared by their reflection, not by a formula: a shoebox's narrow low bands keep
  // a few long-lived modes, so equal reflection does not mean exactly equal T20.)
  ShoeboxRoom room;
  room.size_m = {5, 6, 3};
  room.air_absorption = false;
  BandValues r[2];
  for (std::size_t b = 0; b < kOctaveBands; ++b) {
    r[0][b] = b % 2 ? 0.95 : 0.85;
    r[1][b] = b % 2 ? 0.85 : 0.95;
  }
  std::array<std::optional<double>, kOctaveBands> rt60[2];
  for (int i = 0; i < 2; ++i) {
    for (auto& s : room.reflection) s = r[i];
    rt60[i] = band_rt60_t20_s(image_source_response(room, {3.9, 4.7, 0.8}, {1.0, 2.4, 0.05}, kRate, 5), kRate);
  }
  // 250 Hz to 8 kHz (125 Hz needs a longer response than such a room's to measure well).
  for (std::size_t b = 1; b < 7; ++b) {
    ASSERT_TRUE(rt60[0][b] && rt60[1][b]) << band_name(b);
    std::printf("[ figures  ] band %-6s T20 %.3f s at reflection %.2f, %.3f s at %.2f\n", band_name(b).c_str(),
                *rt60[0][b], r[0][b], *rt60[1][b], r[1][b]);
    const int less = r[0][b] < r[1][b] ? 0 : 1;
    EXPECT_LT(*rt60[less][b] * 1.5, *rt60[1 - less][b]) << band_name(b);
    for (std::size_t c = 1; c < 7; ++c) {
      if (r[0][b] < r[0][c]) {
        EXPECT_LT(*rt60[0][b], *rt60[0][c]) << band_name(b) << " against " << band_name(c);
      }
    }
  }
}
