// Physical layer: the Kaiser window, for the windowed-sinc fractional delays of the
// image-source room and of radial motion.
#pragma once

#include <cmath>

namespace dtmf::sim {

// The Kaiser window at r in [-1, 1] (0 outside), peak 1 at r = 0: I0(beta sqrt(1 - r^2)) / I0(beta).
inline double kaiser(double r, double beta) {
  return std::abs(r) >= 1 ? 0.0 : std::cyl_bessel_i(0.0, beta * std::sqrt(1 - r * r)) / std::cyl_bessel_i(0.0, beta);
}

}  // namespace dtmf::sim
