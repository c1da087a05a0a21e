#pragma once
// The hysteresis of corner events (abs, saturation, dead_zone, lookup
// tables, motion tables).
//
// A block that switches pieces at a corner c leaves its current piece only
// once its input is past c by CornerBand(c): rising above c + band or
// falling below c - band. A signal resting on the corner -- zero made of
// terms that cancel to round-off, a velocity at rest -- then stays on one
// piece instead of switching at every sign flip of its noise (without the
// band, 0.5 s of |sin(6 pi t) - sin(6 pi t + 2 pi)| took 94 events). Inside
// the band the output is the current piece extended past the corner: for
// continuous blocks an error of band times the slope change; an event is
// located band / |u'| late.

#include <algorithm>
#include <cmath>

namespace mechflow::blocks {

inline double CornerBand(double corner) { return 1e-12 * std::max(1.0, std::abs(corner)); }

}  // namespace mechflow::blocks
