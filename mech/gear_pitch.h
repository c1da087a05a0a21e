#pragma once
// Pitch geometry of a gear pair (ELEMENTS.md 6): where the teeth meet (the
// pitch point P) and the direction the tooth force acts in (the pitch
// tangent t), from the global centres O1, O2 and unit axes a1, a2 of the two
// gears and the ratio i = r1/r2. Pure functions of positions, so the pitch
// geometry can be checked by hand; they allocate nothing.
//
// Parallel axes (spur gears):
//   u = unit(O2 - O1 with its a1 component removed), A = its length,
//   r1 = A i / (1 + i), P = O1 + r1 u, t = a1 x u.
// Intersecting axes (bevel gears):
//   apex Q = the intersection of the axis lines (midpoint of their closest
//   points, so a drift of the axes off each other does not matter),
//   e1 = unit(O1 - Q), e2 = unit(O2 - Q), shaft angle S = angle(e1, e2),
//   pitch-cone angle of gear 1: tan g1 = i sin S / (1 + i cos S),
//   n = unit(e2 - (e2.e1) e1) (in the plane of the axes, across axis 1),
//   r1 = |O1 - Q| tan g1, P = O1 + r1 n: the point of the contact
//   generatrix (Q + s (cos g1 e1 + sin g1 n)) on gear 1's pitch circle;
//   t = a1 x n, normal to the plane of the axes.
// In both cases a1 . t = 0 and t is a unit vector, and the sign of a2 plays
// no part; the sign of a1 only flips t (and with it the sign of the mesh
// deflection and force, not the loads).

#include "mech/spatial.h"

namespace mechflow::mech {

enum class GearAxes { kParallel, kIntersecting, kSkew };

// How the axis lines (O1, a1), (O2, a2) (unit axes) lie: parallel when the
// sine of their angle is below 1e-9; intersecting when their common
// perpendicular is shorter than 1e-6 |O2 - O1|; skew otherwise.
// `gap` (optional) receives the length of the common perpendicular [m].
GearAxes ClassifyGearAxes(const Vec3& o1, const Vec3& a1, const Vec3& o2, const Vec3& a2, double* gap = nullptr);

struct PitchGeometry {
  Vec3 p = Vec3::Zero();  // pitch point, global [m]
  Vec3 t = Vec3::Zero();  // pitch tangent, unit, global
  double r1 = 0.0;        // pitch radius of gear 1 [m]
  double shaft_angle = 0.0;  // S [rad]; 0 for parallel axes
  double cone_angle1 = 0.0;  // g1 [rad]; 0 for parallel axes
  // Why the geometry could not be formed (static text), or nullptr.
  const char* problem = nullptr;
};

PitchGeometry ParallelPitch(const Vec3& o1, const Vec3& a1, const Vec3& o2, double ratio);
PitchGeometry BevelPitch(const Vec3& o1, const Vec3& a1, const Vec3& o2, const Vec3& a2, double ratio);

}  // namespace mechflow::mech
