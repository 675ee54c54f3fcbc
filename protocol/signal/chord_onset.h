// Signal layer: where a chord began, from how a tone of it rose across the grid's windows.
//
// A rectangular window that holds L samples of a steady tone on its bin reads the tone's
// amplitude in proportion to L. So across windows a hop apart, a tone's amplitude (or the sum
// of several) rises in a straight line: from the window that ends where the chord's steady
// part begins, to the first window wholly inside it, which holds the full amplitude (the
// plateau). The rise crosses half the plateau at the window that began half a window before the
// steady part. Interpolating that crossing between the two windows either side of it places
// the steady start to a fraction of a hop.
//
// Why: a clean frame decodes from grid windows up to three hops before the ones wholly inside
// its chords (the window astride the first chord's start and the gap reads it right when
// nothing else is there). The grid's own start, which assumes the windows lie inside the
// chords, then named a start up to 40 ms early. The robot times a Velocity's lease and its
// logged start from it. (The fast listener takes the earliest of a chord's tones: in a room a
// tone whose reverberation outweighs its direct sound rises late; hop_reader.cpp.)
// Pure arithmetic, no I/O.
#pragma once

#include <optional>
#include <span>

namespace dtmf::signal {

// Where the chord's steady part began, in samples after the start of window 0, or nothing
// when the amplitudes show no rise. `amplitude[k]`: the magnitude of a tone of the chord (or
// the sum of several) in the window that starts k hops after window 0. Window 0 must lie wholly before the chord
// (its amplitude is the floor), and some window wholly inside it (its amplitude the plateau).
// `min_rise`: the plateau must stand this many times over the floor to be read at all.
std::optional<double> chord_steady_start(std::span<const float> amplitude, int window_samples, int hop_samples,
                                         float min_rise);

}  // namespace dtmf::signal
