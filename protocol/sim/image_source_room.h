// Physical layer, rooms: the impulse response of a shoebox room by the image-source method
// (Allen and Berkley 1979, "Image method for efficiently simulating small-room acoustics").
//
// Each reflection path from the loudspeaker to the microphone is a straight line from an
// image of the loudspeaker, mirrored in the walls; its amplitude is the product of the
// reflection coefficients of the walls it met, over its length (so the direct sound is
// 1/d: 1 at 1 m, the level a transmitter's samples stand for), times air absorption over
// that length. Reflection and absorption depend on frequency, so every image adds its
// amplitude in each octave band (125 Hz .. 16 kHz) to that band's impulse train; each train
// is filtered to its band (octave_bands.h: zero-phase, bands summing to 1) and the bands
// are summed, as pyroomacoustics does.
//   - The direct sound and every image arriving within kFractionalDelayS of it land at
//     their exact, fractional times (a 64-tap Kaiser-windowed sinc), so the direct sound
//     and the first reflections arrive at path length / 343 m/s to a small part of a sample.
//   - Images of second and higher order are displaced at random by up to randomization_m
//     on each axis (the randomized image method, De Sena et al. 2015, with
//     pyroomacoustics' 8 cm): a perfect shoebox's regular lattice of images otherwise rings
//     with flutter and sweeping echoes no real room has. Later images land on the nearest
//     sample (half a sample is 3.6 mm at 48 kHz, well within that randomness).
//   - The response is generated until its energy decay curve has fallen 60 dB, estimated
//     from the slowest axial decay and cut at the measured -60 dB point, and at most
//     max_length_s (and at most kMaxImages images, which bounds the time it takes).
// The method is reciprocal: swapping the loudspeaker and the microphone gives the same
// response, exactly (the pair is put in a fixed order before the images are made).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/octave_bands.h"

namespace dtmf::sim {

struct Point3 {
  double x = 0, y = 0, z = 0;  // metres; z up, the floor at z = 0
};

enum Surface : std::size_t { kWallX0, kWallX1, kWallY0, kWallY1, kFloor, kCeiling, kSurfaces };

inline constexpr double kFractionalDelayS = 0.05;
inline constexpr double kMaxImages = 4e7;
inline constexpr double kMinRoomSideM = 0.5, kMaxRoomSideM = 200;
// How close to a surface a loudspeaker or microphone may be, and to each other.
inline constexpr double kMinInsideM = 0.01;
inline constexpr double kDefaultWallReflection = 0.9;    // walls and ceiling: a furnished room
inline constexpr double kDefaultFloorReflection = 0.97;  // a hard floor: tiles, wood, concrete (absorbs 6 %)

struct ShoeboxRoom {
  Point3 size_m{7, 9, 3};
  // Amplitude (pressure) reflection coefficient of each surface in each octave band, in
  // [0, 1); absorption is 1 - r^2.
  std::array<BandValues, kSurfaces> reflection = {
      uniform_bands(kDefaultWallReflection),  uniform_bands(kDefaultWallReflection),
      uniform_bands(kDefaultWallReflection),  uniform_bands(kDefaultWallReflection),
      uniform_bands(kDefaultFloorReflection), uniform_bands(kDefaultWallReflection)};
  bool air_absorption = true;  // the channel's fit to ISO 9613-1, per band centre
  double max_length_s = 2.5;
  double randomization_m = 0.08;  // 0: the plain image method
};

// The room's checks and measures (shoebox_checks.cpp).
std::string surface_name(Surface s);

// std::invalid_argument naming what is wrong and what to do: a side outside
// [kMinRoomSideM, kMaxRoomSideM], a coefficient outside [0, 1), a bad length or randomization.
void check_room(const ShoeboxRoom& room);
// std::invalid_argument unless `p` lies inside the room (at least 1 cm from every surface).
void check_inside(const ShoeboxRoom& room, const Point3& p, const std::string& what);

double distance_m(const Point3& a, const Point3& b);

// The response from a loudspeaker at `speaker` to a microphone at `mic`. length_s > 0
// generates exactly that long (no cut at -60 dB); 0 chooses as described above.
std::vector<float> image_source_response(const ShoeboxRoom& room, const Point3& speaker, const Point3& mic,
                                         int sample_rate_hz, std::uint64_t seed, double length_s = 0);

}  // namespace dtmf::sim
