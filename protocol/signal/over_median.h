// Signal layer: whether a level stands a given ratio over the median of a band's powers —
// the frame and reply listeners' test of a tone against its band's floor.
//
// level > ratio · median holds exactly when more than half of the powers v have
// ratio · v < level (ratio · v grows with v, so those are the smallest, and the median is
// the middle one of them, index n / 2 once sorted). Counting them needs neither a copy nor a
// partial sort: the listeners make this test for every band of every window or candidate.
// Header-only, pure arithmetic.
#pragma once

#include <cstddef>
#include <span>

namespace dtmf::signal {

// `ratio` > 0. For n powers, the median is the (n / 2 + 1)-th smallest.
inline bool over_median(std::span<const float> powers, float level, float ratio) {
  std::size_t under = 0;
  for (const float v : powers) under += ratio * v < level ? 1 : 0;
  return under > powers.size() / 2;
}

}  // namespace dtmf::signal
