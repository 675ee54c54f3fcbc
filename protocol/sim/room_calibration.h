// Physical layer, rooms: a shoebox room tuned to a reverberation time.
//
// Asked for an RT60, this finds the one reflection coefficient that the four walls and
// the ceiling share (in every band) for which the generated response's measured T20
// (room_decay.h, broadband) is that RT60; the floor keeps its own coefficients. Why not a
// formula: Sabine and Eyring assume a diffuse field, which a shoebox with a hard floor is
// not — sound trapped between a hard floor and the ceiling decays more slowly than the
// average absorption says (a 7 x 9 x 3 m room measured T20 0.84 s where Eyring said
// 0.47 s). So the coefficient is found by measurement: Eyring's value to start, then
// steps that assume RT60 proportional to 1 / -ln(r) (nearly true), kept inside a bracket
// that shrinks by bisection if a step overshoots, until the measured RT60 is within 2 %.
// Each try generates the response only as long as T20 needs (three quarters of the RT60
// asked for, after the direct sound), with the same seed as the final one.
#pragma once

#include <cstdint>

#include "sim/image_source_room.h"

namespace dtmf::sim {

struct CalibratedRoom {
  ShoeboxRoom room;       // walls and ceiling set to `reflection`
  double reflection = 0;  // the coefficient found
  double rt60_s = 0;      // T20 of the response it gives (what was reached)
  int tries = 0;
};

// Throws std::invalid_argument for an RT60 outside [0.1 s, room.max_length_s] or one this
// room cannot reach (with the closest it got).
CalibratedRoom calibrate_rt60(const ShoeboxRoom& room, const Point3& speaker, const Point3& mic, double rt60_s,
                              int sample_rate_hz, std::uint64_t seed);

// Eyring's reverberation time of the room, seconds (for comparison and a first guess).
double eyring_rt60_s(const ShoeboxRoom& room);

}  // namespace dtmf::sim
