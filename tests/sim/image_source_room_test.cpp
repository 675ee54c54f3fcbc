// The image-source room against geometry: when and how loud the direct sound and the
// first reflections arrive, reciprocity, refusals, and how long a big room takes.
#include <gtest/gtest.h>

#include <chrono>

#include "room_test_support.h"
#include "sim/image_source_room.h"
#include "sim/room_calibration.h"
#include "sim/room_decay.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

Point3 mirror(Point3 p, int axis, double plane) {
  double* c = axis == 0 ? &p.x : axis == 1 ? &p.y : &p.z;
  *c = 2 * plane - *c;
  return p;
}

}  // namespace

TEST(ImageSourceRoom, DirectSoundFloorAndWallReflectionsArriveAtPathLengthOverTheSpeedOfSound) {
  // One reflecting surface at a time, all else absorbing, so each reflection stands alone
  // (with the floor and a wall together, the wall's reflection has a floor-reflected twin
  // 3 samples behind it). No air, no randomization.
  const Point3 speaker{1.5, 2.3, 1.2}, mic{3.5, 2.6, 0.05};  // a robot's microphone, 5 cm up
  struct Case {
    const char* what;
    Surface surface;
    double reflection;
    Point3 image;
  };
  const Case cases[] = {{"floor", kFloor, 0.9, mirror(speaker, 2, 0.0)},
                        {"wall x=0", kWallX0, 0.8, mirror(speaker, 0, 0.0)}};
  for (const auto& c : cases) {
    ShoeboxRoom room;
    room.size_m = {6, 5, 3};
    for (auto& r : room.reflection) r = uniform_bands(0.0);
    room.reflection[c.surface] = uniform_bands(c.reflection);
    room.air_absorption = false;
    room.randomization_m = 0;
    const auto h = image_source_response(room, speaker, mic, kRate, 1, 0.1);
    const double arrivals[2][2] = {{distance_m(speaker, mic), 1.0}, {distance_m(c.image, mic), c.reflection}};
    for (const auto& [path_m, reflection] : arrivals) {
      const double expected_samples = path_m / kSpeedOfSoundMps * kRate;
      const auto [t, height] = peak_near(h, expected_samples);
      EXPECT_NEAR(t, expected_samples, 1.0) << c.what << ", path " << path_m << " m";
      EXPECT_NEAR(height, reflection / path_m, 0.03 * reflection / path_m) << c.what << ", path " << path_m << " m";
    }
    // Nothing else arrives: the rest of the response is silent.
    const auto last = static_cast<std::size_t>(distance_m(c.image, mic) / kSpeedOfSoundMps * kRate) + 40;
    EXPECT_LT(rms(std::span(h).subspan(last)), 1e-4) << c.what;
  }
  // The floor's path is 5 cm (7 samples) longer than the direct one: a notch at 3.3 kHz.
  EXPECT_NEAR(distance_m(cases[0].image, mic) - distance_m(speaker, mic), 0.052, 0.002);
}

TEST(ImageSourceRoom, ReciprocalAndDeterministicForASeed) {
  ShoeboxRoom room;
  room.size_m = {4, 5, 2.7};
  const Point3 a{1.0, 2.0, 0.05}, b{3.1, 3.9, 0.8};
  const auto ab = image_source_response(room, a, b, kRate, 7);
  EXPECT_EQ(ab, image_source_response(room, b, a, kRate, 7));
  EXPECT_EQ(ab, image_source_response(room, a, b, kRate, 7));
  EXPECT_NE(ab, image_source_response(room, a, b, kRate, 8)) << "the seed moves the late images";
}

TEST(ImageSourceRoom, RefusesWhatCannotBeARoom) {
  ShoeboxRoom room;
  const Point3 inside{1, 1, 1};
  auto message = [&](ShoeboxRoom r, Point3 s, Point3 m) -> std::string {
    try {
      image_source_response(r, s, m, kRate, 1);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(message(room, inside, {1, 1, 3.5}).find("the microphone at"), std::string::npos);
  EXPECT_NE(message(room, {-1, 1, 1}, inside).find("the loudspeaker"), std::string::npos);
  ShoeboxRoom bad = room;
  bad.reflection[kFloor][3] = 1.0;
  EXPECT_NE(message(bad, inside, {2, 2, 1}).find("floor at 1 kHz: give a value in [0, 1)"), std::string::npos);
  bad = room;
  bad.size_m.y = 0.1;
  EXPECT_NE(message(bad, inside, {2, 2, 1}).find("room side"), std::string::npos);
  bad.size_m.y = 1e6;
  EXPECT_NE(message(bad, inside, {2, 2, 1}).find("room side"), std::string::npos);
  EXPECT_NE(message(room, inside, inside).find("less than 1 cm apart"), std::string::npos);
}

TEST(ImageSourceRoom, ARoomWithRt60OfOneAndAHalfSecondsIsMadeInAFewSeconds) {
  ShoeboxRoom room;
  room.size_m = {7, 9, 3};
  const Point3 speaker{5.2, 6.4, 0.8}, mic{1.0, 3.6, 0.05};
  const auto start = std::chrono::steady_clock::now();
  const CalibratedRoom tuned = calibrate_rt60(room, speaker, mic, 1.5, kRate, 1);
  const double calibrate_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto h = image_source_response(tuned.room, speaker, mic, kRate, 1);
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto rt60 = rt60_t20_s(h, kRate);
  ASSERT_TRUE(rt60);
  std::printf(
      "[ figures  ] 7x9x3 m, floor 0.97: walls %.4f for RT60 1.5 s (Eyring with them: %.2f s); "
      "T20 %.3f s, %.2f s long; calibration %.2f s (%d tries), total %.2f s\n",
      tuned.reflection, eyring_rt60_s(tuned.room), *rt60, static_cast<double>(h.size()) / kRate, calibrate_s,
      tuned.tries, total_s);
  EXPECT_NEAR(*rt60, 1.5, 0.15);
  EXPECT_LT(total_s, 8.0);
}
