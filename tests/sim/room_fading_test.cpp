// Frequency-selective fading, the reason for the rooms: in a reverberant room the power
// response |H(f)|^2 at a point is a sum of many reflections with random phases, so it is
// spread like an exponential (Rayleigh amplitudes): 1 - e^-0.1 = 9.5 % of frequencies lie
// more than 10 dB below the mean and 1 % more than 20 dB below. A chord's tones that fall
// into such fades are lost. The old diffuse reverberator has hardly any fades; the
// image-source room and the measured rooms have them.
#include <gtest/gtest.h>

#include "room_test_support.h"
#include "sim/image_source_room.h"
#include "sim/measured_rir.h"
#include "sim/room_calibration.h"

using namespace dtmf::sim;
using namespace dtmf::room_test;

namespace {

void print(const char* what, const FadeStats& s) {
  std::printf(
      "[ figures  ] %-44s %5.1f %% of 4-16 kHz more than 10 dB down, %4.1f %% more than 20 dB (%zu frequencies)\n",
      what, 100 * s.fraction_10(), 100 * s.fraction_20(), s.frequencies);
}

}  // namespace

TEST(RoomFading, AnImageSourceRoomFadesLikeADiffuseFieldAndTheOldReverberatorHardlyAtAll) {
  // Four microphone positions 4 to 5.5 m from the loudspeaker, pooled: 1924 frequencies,
  // so that 1 % is 19 of them and chance does not decide.
  ShoeboxRoom room;
  room.size_m = {6, 8, 3};
  const Point3 speaker{4.3, 5.4, 0.8};
  const CalibratedRoom tuned = calibrate_rt60(room, speaker, {1.0, 3.2, 0.05}, 0.8, kRate, 1);
  FadeStats ism, diffuse;
  for (int i = 0; i < 4; ++i) {
    const Point3 mic{1.0 + 0.2 * i, 3.2 - 0.5 * i, 0.05};
    ism += fade_stats(image_source_response(tuned.room, speaker, mic, kRate, 1));
    ChannelConfig old;
    old.reverb.rt60_s = 0.8;
    AcousticChannel schroeder(kRate, old);
    schroeder.add_transmitter(distance_m(speaker, mic));
    diffuse += fade_stats(impulse_response(schroeder, 2.0));
  }
  print("image-source 6x8x3 m, RT60 0.8 s, 4-5.5 m", ism);
  EXPECT_GT(ism.fraction_10(), 0.05);
  EXPECT_LT(ism.fraction_10(), 0.15);
  EXPECT_GE(ism.fraction_20(), 0.005);
  print("Schroeder reverberator, RT60 0.8 s, 4-5.5 m", diffuse);
  EXPECT_LT(diffuse.fraction_10(), 0.02) << "the direct sound dominates its weak, dense tail";
  EXPECT_LT(diffuse.fraction_10(), ism.fraction_10() / 3);
  EXPECT_LT(diffuse.fraction_20(), 0.002);
}

TEST(RoomFading, TheMeasuredRoomsFadeAsDeeply) {
  for (const char* name : {"seminar_room_clap.wav", "studio_live_room.wav", "smoking_room.wav"}) {
    const MeasuredRir rir = load_measured_rir(rir_path(name), kRate);
    const FadeStats s = fade_stats(rir.samples);
    print(name, s);
    EXPECT_GT(s.fraction_10(), 0.05) << name;
    EXPECT_GE(s.fraction_20(), 0.004) << name;
  }
}
